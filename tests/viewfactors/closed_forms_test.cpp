// Matrices against Howell's closed forms (tests/formfactor/howell.h: C-11 parallel opposed
// rectangles, C-14 perpendicular rectangles with a common edge), evaluated in quad precision.
#include <gtest/gtest.h>

#include "../formfactor/howell.h"
#include "viewfactor_test_scenes.h"

namespace hrad::test {
namespace {

// Expected F between walls k -> l of make_box(a, b, c) (walls: y=0, y=b, x=0, x=a, z=0, z=c).
double box_factor(int k, int l, double a, double b, double c) {
  const int ak = k / 2, al = l / 2;  // axis of the wall's normal: 0 -> y, 1 -> x, 2 -> z
  const double size[3] = {b, a, c};  // extent along each normal axis
  if (k == l) return 0.0;
  if (ak == al) {
    // Opposite walls: the two extents other than the normal's, at the normal's distance.
    const double d = size[ak], e1 = size[(ak + 1) % 3], e2 = size[(ak + 2) % 3];
    return howell_c11(e1, e2, d);
  }
  // Adjacent walls: common edge along the third axis; w = k's extent along l's normal, h = l's
  // extent along k's normal.
  const int third = 3 - ak - al;
  return howell_c14(size[third], size[al], size[ak]);
}

// A unit cube: 0.199825 opposite, 0.200044 adjacent (Howell C-11 and C-14 at 1), to 1e-10.
TEST(ViewFactorClosedForms, UnitCube) {
  const Scene s = make_box(1, 1, 1, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0});
  const ViewFactorMatrix m = compute_view_factors(s, face_units(s), plain_options());
  EXPECT_NEAR(m.factor(0, 1), 0.199825, 5e-7);
  EXPECT_NEAR(m.factor(0, 2), 0.200044, 5e-7);
  for (int k = 0; k < 6; ++k)
    for (int l = 0; l < 6; ++l) EXPECT_NEAR(m.factor(k, l), box_factor(k, l, 1, 1, 1), 1e-10) << k << " -> " << l;
}

// Boxes over aspect ratios 1e-2..1e2: every entry of the 6 x 6 matrix against C-11 / C-14 (1e-10
// absolute and relative), rows summing to 1 within 1e-10 (a convex enclosure: all pairs visible).
TEST(ViewFactorClosedForms, BoxesOverAspectRatios) {
  const double dims[][3] = {{1, 1, 1}, {10, 1, 0.1}, {0.01, 1, 1}, {100, 1, 1}, {1, 100, 0.5}, {3, 0.02, 7}};
  for (const auto& d : dims) {
    const Scene s = make_box(d[0], d[1], d[2], {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0});
    const ViewFactorMatrix m = compute_view_factors(s, face_units(s), plain_options());
    for (int k = 0; k < 6; ++k) {
      EXPECT_NEAR(m.row_sum(k), 1.0, 1e-10);
      for (int l = 0; l < 6; ++l) {
        const double want = box_factor(k, l, d[0], d[1], d[2]);
        EXPECT_NEAR(m.factor(k, l), want, std::max(1e-10 * want, 1e-14))
            << d[0] << "x" << d[1] << "x" << d[2] << " " << k << "->" << l;
      }
    }
  }
}

// Two parallel opposed rectangles (an open model) over aspect ratios: C-11 to 1e-10 relative, and
// the sky takes the rest (1 - F, the report's remainder).
TEST(ViewFactorClosedForms, ParallelRectanglesOpenModel) {
  for (const double c : {0.001, 0.1, 1.0, 10.0, 1000.0})
    for (const double a : {0.05, 1.0, 20.0}) {
      Scene s;
      s.materials = {material(Rgb::Constant(0.5), Rgb::Zero())};
      add_polygon(s, {{0, 0, 0}, {a, 0, 0}, {a, 1, 0}, {0, 1, 0}}, Vec3::UnitZ(), 0);
      add_polygon(s, {{0, 0, c}, {a, 0, c}, {a, 1, c}, {0, 1, c}}, -Vec3::UnitZ(), 0);
      const ViewFactorMatrix m = compute_view_factors(s, face_units(s), plain_options());
      const double want = howell_c11(a, 1, c);
      EXPECT_LE(relative_error(m.factor(0, 1), want), 1e-10) << a << " at " << c;
      EXPECT_NEAR(1.0 - m.row_sum(0), 1.0 - want, 1e-10 * want);
    }
}

// Perpendicular rectangles with a common edge (C-14) over wide aspect ratios, both directions.
TEST(ViewFactorClosedForms, PerpendicularRectangles) {
  for (const double w : {0.001, 0.1, 1.0, 10.0, 500.0})
    for (const double h : {0.01, 1.0, 50.0}) {
      Scene s;
      s.materials = {material(Rgb::Constant(0.5), Rgb::Zero())};
      add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, w, 0}, {0, w, 0}}, Vec3::UnitZ(), 0);
      add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 0, h}, {0, 0, h}}, Vec3::UnitY(), 0);
      const ViewFactorMatrix m = compute_view_factors(s, face_units(s), plain_options());
      EXPECT_LE(relative_error(m.factor(0, 1), howell_c14(1, w, h)), 1e-10) << w << " " << h;
      EXPECT_LE(relative_error(m.factor(1, 0), howell_c14(1, h, w)), 1e-10) << w << " " << h;
    }
}

// A box 2a x b x c split at x = a by a two-sided partition (two coincident patches facing either
// way), its walls cut at the partition: each half is a closed a x b x c box (C-11, C-14 to 1e-10),
// and nothing crosses the partition (exactly 0: hidden pairs, or sampled rays all blocked).
TEST(ViewFactorClosedForms, BoxSplitByPartition) {
  const double a = 1.5, b = 1.0, c = 0.7;
  Scene s;
  s.materials = {material(Rgb::Constant(0.5), Rgb::Zero())};
  // Walls in make_box order for each half, so half h's wall k is face 6 h + k.
  for (int h = 0; h < 2; ++h) {
    const double x0 = h * a, x1 = x0 + a;
    const Vec3 centre((x0 + x1) / 2, b / 2, c / 2);
    auto wall = [&](std::vector<Vec3> v) { add_polygon(s, v, centre - polygon_centroid(v), 0); };
    wall({{x0, 0, 0}, {x1, 0, 0}, {x1, 0, c}, {x0, 0, c}});
    wall({{x0, b, 0}, {x1, b, 0}, {x1, b, c}, {x0, b, c}});
    wall({{x0, 0, 0}, {x0, b, 0}, {x0, b, c}, {x0, 0, c}});
    wall({{x1, 0, 0}, {x1, b, 0}, {x1, b, c}, {x1, 0, c}});
    wall({{x0, 0, 0}, {x1, 0, 0}, {x1, b, 0}, {x0, b, 0}});
    wall({{x0, 0, c}, {x1, 0, c}, {x1, b, c}, {x0, b, c}});
  }
  const ViewFactorMatrix m = compute_view_factors(s, face_units(s), plain_options());
  for (int i = 0; i < 12; ++i) {
    EXPECT_NEAR(m.row_sum(i), 1.0, 1e-10) << i;
    for (int j = 0; j < 12; ++j) {
      const double want = i / 6 == j / 6 ? box_factor(i % 6, j % 6, a, b, c) : 0.0;
      EXPECT_NEAR(m.factor(i, j), want, 1e-10 * std::max(want, 1e-4)) << i << " -> " << j;
    }
  }
}

}  // namespace
}  // namespace hrad::test
