// Point-to-surface factors (point_factors.h) against Howell's B-3 (a plane element to a parallel
// rectangle, its normal through a corner), with and without an occluder whose shadow is a known
// quadrant: exact (visible regions), so to 1e-12.
#include <gtest/gtest.h>

#include "../formfactor/howell.h"
#include "hrad/viewfactors/point_factors.h"
#include "viewfactor_test_scenes.h"

namespace hrad::test {
namespace {

// A point at the origin facing +z; a 2 x 2 square centred above it at z = 2 (facing down) and a
// 0.5 x 0.5 plate at z = 1 over the quadrant x, y in [0, 0.5] (facing down), whose shadow on the
// square is the quadrant [0, 1]^2. By symmetry the square is four B-3 quadrants B3(1, 1, 2); the
// plate hides one, and the plate itself is B3(0.5, 0.5, 1).
TEST(PointFactors, OccludedQuadrantIsExact) {
  Scene s;
  s.materials = {material(Rgb::Constant(0.5), Rgb::Zero())};
  add_polygon(s, {{-1, -1, 2}, {1, -1, 2}, {1, 1, 2}, {-1, 1, 2}}, -Vec3::UnitZ(), 0);
  const ProbePoint x{Vec3::Zero(), Vec3::UnitZ(), 0};
  const SurfaceUnits open = face_units(s);
  const PointFactors a = point_view_factors(s, open, std::span<const ProbePoint>(&x, 1));
  EXPECT_NEAR(a.at(0, 0), 4 * howell_b3(1, 1, 2), 1e-12);

  add_polygon(s, {{0, 0, 1}, {0.5, 0, 1}, {0.5, 0.5, 1}, {0, 0.5, 1}}, -Vec3::UnitZ(), 0);
  const PointFactors b = point_view_factors(s, face_units(s), std::span<const ProbePoint>(&x, 1));
  EXPECT_EQ(b.partial, 1u);
  EXPECT_NEAR(b.at(0, 0), 3 * howell_b3(1, 1, 2), 1e-12);
  EXPECT_NEAR(b.at(0, 1), howell_b3(0.5, 0.5, 1), 1e-12);
  // A point facing away sees nothing.
  const ProbePoint down{Vec3::Zero(), -Vec3::UnitZ(), 0};
  const PointFactors c = point_view_factors(s, face_units(s), std::span<const ProbePoint>(&down, 1));
  EXPECT_EQ(c.at(0, 0), 0.0);
  EXPECT_EQ(c.at(0, 1), 0.0);
}

// Inside a closed box every point's factors sum to 1 (closure at a point) within 1e-12, with an
// occluding block inside the box.
TEST(PointFactors, ClosedRoomPointsSumToOne) {
  Scene s = make_box(4, 3, 5, {material(Rgb::Constant(0.5), Rgb::Zero())}, {0, 0, 0, 0, 0, 0}, true);
  add_block(s, 1.0, 2.5, 0.8, 1.7, 1.5, 3.0, 0);
  const std::vector<ProbePoint> points = {{Vec3(2, 0.5, 2.2), Vec3(0, 1, 0), 0},
                                          {Vec3(0.5, 1.2, 4.0), Vec3(1, 0.2, -1).normalized(), 0},
                                          {Vec3(3.5, 2.0, 0.5), Vec3(-1, -1, 1).normalized(), 0}};
  const PointFactors f = point_view_factors(s, face_units(s), points);
  EXPECT_GT(f.partial, 0u);
  for (int i = 0; i < f.points; ++i) {
    double sum = 0.0;
    for (int u = 0; u < f.units; ++u) {
      EXPECT_GE(f.at(i, u), 0.0);
      sum += f.at(i, u);
    }
    EXPECT_NEAR(sum, 1.0, 1e-12) << i;
  }
}

}  // namespace
}  // namespace hrad::test
