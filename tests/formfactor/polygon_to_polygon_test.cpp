// Polygon to polygon against Howell's closed forms (C-11, C-14) over aspect ratios and distances,
// split into triangles (skew edges, shared vertices), clipped, far apart, rescaled; exact zeros.
#include "hrad/formfactor/polygon_to_polygon.h"

#include <gtest/gtest.h>

#include "howell.h"
#include "hrad/geometry/polygon.h"
#include "test_geometry.h"

namespace hrad::test {
namespace {

const double kAspects[] = {0.01, 0.1, 0.3, 1.0, 2.5, 7.0, 30.0, 100.0};
const double kDistances[] = {1e-3, 0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 100.0, 1e3};

// C-11 plates: from = [0,a]x[0,b] at z = 0 facing +z, to = the same at z = c facing -z.
std::pair<Polygon, Polygon> c11_pair(double a, double b, double c) {
  return {rectangle(Vec3::Zero(), Vec3(a, 0, 0), Vec3(0, b, 0)),
          rectangle(Vec3(0, 0, c), Vec3(0, b, 0), Vec3(a, 0, 0))};
}

// C-14: common edge [0,l] on the x axis; from in z = 0 (width w along y, facing +z), to in y = 0
// (height h along z, facing +y).
std::pair<Polygon, Polygon> c14_pair(double l, double w, double h) {
  return {rectangle(Vec3::Zero(), Vec3(l, 0, 0), Vec3(0, w, 0)), rectangle(Vec3::Zero(), Vec3(0, 0, h), Vec3(l, 0, 0))};
}

// Sum of A_i F_ij over the triangles of both rectangles (different diagonals), divided by A_from.
double triangulated(const Polygon& a, const Polygon& b) {
  const Polygon pieces_a[] = {{a[0], a[1], a[2]}, {a[0], a[2], a[3]}};
  const Polygon pieces_b[] = {{b[0], b[1], b[3]}, {b[1], b[2], b[3]}};
  double sum = 0.0;
  for (const Polygon& x : pieces_a)
    for (const Polygon& y : pieces_b) sum += polygon_area(x) * polygon_to_polygon(x, y).from_to;
  return sum / polygon_area(a);
}

TEST(PolygonToPolygon, HowellC11ParallelRectangles) {
  std::mt19937_64 rng(11);
  for (double a : kAspects)
    for (double c : kDistances) {
      const auto [from, to] = c11_pair(a, 1.0, c);
      const double exact = howell_c11(a, 1.0, c);
      const PairFormFactor f = polygon_to_polygon(from, to);
      EXPECT_LE(relative_error(f.from_to, exact), 1e-11) << "a=" << a << " c=" << c;
      EXPECT_LE(relative_error(f.to_from, exact), 1e-11) << "a=" << a << " c=" << c;
      // Any rigid motion of the pair.
      const Eigen::Matrix3d rot = random_rotation(rng);
      const Vec3 shift = 10.0 * random_unit(rng);
      EXPECT_LE(relative_error(polygon_to_polygon(moved(from, rot, shift), moved(to, rot, shift)).from_to, exact),
                1e-11)
          << "moved a=" << a << " c=" << c;
    }
}

TEST(PolygonToPolygon, HowellC14PerpendicularRectanglesWithCommonEdge) {
  const double sizes[] = {1e-3, 0.01, 0.3, 1.0, 7.0, 100.0, 1e3};
  for (double w : sizes)
    for (double h : sizes) {
      const auto [from, to] = c14_pair(1.0, w, h);
      const double exact = howell_c14(1.0, w, h);
      const PairFormFactor f = polygon_to_polygon(from, to);
      EXPECT_LE(relative_error(f.from_to, exact), 1e-11) << "w=" << w << " h=" << h;
      // Reciprocity: F_to_from = A_from F_from_to / A_to, the same closed form with w and h swapped.
      EXPECT_LE(relative_error(f.to_from, howell_c14(1.0, h, w)), 1e-11) << "w=" << w << " h=" << h;
    }
}

TEST(PolygonToPolygon, TriangulatedPairsAddUp) {
  // Skew edges (the diagonals), shared edges and shared vertices between the pieces.
  const double sizes[] = {0.01, 0.3, 1.0, 7.0, 100.0};
  for (double w : sizes)
    for (double h : sizes) {
      const auto [from, to] = c14_pair(1.0, w, h);
      EXPECT_LE(relative_error(triangulated(from, to), howell_c14(1.0, w, h)), 1e-11) << "w=" << w << " h=" << h;
    }
  for (double a : {0.01, 0.3, 1.0, 7.0, 100.0})
    for (double c : {0.01, 0.3, 1.0, 10.0, 1e3}) {
      const auto [from, to] = c11_pair(a, 1.0, c);
      EXPECT_LE(relative_error(triangulated(from, to), howell_c11(a, 1.0, c)), 1e-11) << "a=" << a << " c=" << c;
    }
}

TEST(PolygonToPolygon, SliversOfAspect1e3) {
  // Documented accuracy limit: long slivers at a distance of a tenth of their length cancel in the
  // contour sum by ~1/aspect and are too close for the far-field quadrature (about 2e-11 here).
  for (double c : {1e-3, 0.01, 0.1, 1.0, 10.0}) {
    const auto [from, to] = c11_pair(1e-3, 1.0, c);
    EXPECT_LE(relative_error(polygon_to_polygon(from, to).from_to, howell_c11(1e-3, 1.0, c)), 1e-10) << c;
  }
}

TEST(PolygonToPolygon, FarApart) {
  // Howell C-11 for distance/size up to 1e5; beyond, the first two terms of the kernel's expansion
  // F = A/(pi c^2) (1 - 2 <rho^2>/c^2 + O(c^-4)), <rho^2> = (a^2 + b^2)/6 for opposed plates.
  for (double c : {1e3, 1e4, 1e5}) {
    const auto [from, to] = c11_pair(1.0, 0.5, c);
    EXPECT_LE(relative_error(polygon_to_polygon(from, to).from_to, howell_c11(1.0, 0.5, c)), 1e-11) << c;
  }
  for (double c : {1e6, 1e7, 1e9}) {
    const double a = 1.0, b = 0.5;
    const auto [from, to] = c11_pair(a, b, c);
    const double expansion = a * b / (M_PI * c * c) * (1.0 - (a * a + b * b) / (3.0 * c * c));
    EXPECT_LE(relative_error(polygon_to_polygon(from, to).from_to, expansion), 1e-11) << c;
  }
}

TEST(PolygonToPolygon, EachPolygonClippedToTheOthersFront) {
  // C-14 with the wall reaching below the floor and the floor reaching behind the wall: only the
  // parts in front of each other count, so the factors equal C-14's times the area ratios.
  const double w = 0.7, h = 1.3;
  const Polygon floor = rectangle(Vec3(0, -2.0, 0), Vec3(1, 0, 0), Vec3(0, w + 2.0, 0));
  const Polygon wall = rectangle(Vec3(0, 0, -3.0), Vec3(0, 0, h + 3.0), Vec3(1, 0, 0));
  const PairFormFactor f = polygon_to_polygon(floor, wall);
  EXPECT_LE(relative_error(f.from_to * (w + 2.0) / w, howell_c14(1.0, w, h)), 1e-11);
  EXPECT_LE(relative_error(f.to_from * (h + 3.0) / h, howell_c14(1.0, h, w)), 1e-11);
}

TEST(PolygonToPolygon, ExactZeros) {
  const auto [from, to] = c11_pair(1.0, 1.0, 1.0);
  auto zero = [](const Polygon& a, const Polygon& b) {
    const PairFormFactor f = polygon_to_polygon(a, b);
    return f.from_to == 0.0 && f.to_from == 0.0;
  };
  EXPECT_TRUE(zero(reversed(from), to));            // from faces away
  EXPECT_TRUE(zero(from, reversed(to)));            // to faces away
  EXPECT_TRUE(zero(reversed(from), reversed(to)));  // back to back
  // Coplanar: adjacent, overlapping, apart; also rotated off the axes.
  const Polygon next = rectangle(Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  const Polygon overlap = rectangle(Vec3(0.5, 0.5, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_TRUE(zero(from, next));
  EXPECT_TRUE(zero(from, overlap));
  EXPECT_TRUE(zero(from, reversed(next)));
  std::mt19937_64 rng(3);
  for (int k = 0; k < 50; ++k) {
    const Eigen::Matrix3d rot = random_rotation(rng);
    const Vec3 shift = random_unit(rng) * 100.0;
    EXPECT_TRUE(zero(moved(from, rot, shift), moved(next, rot, shift))) << k;
    EXPECT_TRUE(zero(moved(from, rot, shift), moved(overlap, rot, shift))) << k;
  }
  // to entirely behind from's plane (facing it) and from behind to's plane.
  const Polygon below = rectangle(Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_TRUE(zero(from, below));
  EXPECT_TRUE(zero(below, from));
  // Touching only along a line in each other's plane (a wall standing behind the floor's edge, facing away).
  EXPECT_TRUE(zero(rectangle(Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1, 0)),
                   rectangle(Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 0, 1))));
  // Degenerate input.
  EXPECT_TRUE(zero(Polygon{Vec3(0, 0, 1), Vec3(1, 0, 1)}, from));
  EXPECT_TRUE(zero(from, Polygon{Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(2, 0, 1)}));
}

TEST(PolygonToPolygon, UnitIndependent) {
  const auto [from, to] = c14_pair(1.0, 0.6, 2.0);
  const Polygon tilted_to = moved(to, Eigen::AngleAxisd(0.3, Vec3::UnitX()).toRotationMatrix(), Vec3(0.2, 0.1, 0.05));
  const PairFormFactor reference = polygon_to_polygon(from, tilted_to);
  ASSERT_GT(reference.from_to, 0.05);
  for (double s : {1e-8, 1e-5, 1e-2, 1e2, 1e5, 1e8}) {
    const Vec3 shift = Vec3(3.0, -1.0, 2.0) * s;
    const PairFormFactor f = polygon_to_polygon(moved(from, Eigen::Matrix3d::Identity(), shift, s),
                                                moved(tilted_to, Eigen::Matrix3d::Identity(), shift, s));
    EXPECT_LE(relative_error(f.from_to, reference.from_to), 1e-12) << s;
    EXPECT_LE(relative_error(f.to_from, reference.to_from), 1e-12) << s;
  }
}

TEST(PolygonToPolygon, AbsoluteToleranceBoundsTheErrorOfAPairThatBarelySeesItself) {
  // A large square grazing the plane of a small one: only a sliver of each lies in front of the
  // other, the factor is ~1e-10 and its contour sum cancels. With abs_tol the answer is within
  // abs_tol times the smaller area of the full-precision one (in exchange units), whatever the cost
  // of the latter.
  const Polygon small = rectangle(Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1, 0));
  // Tilted by 1e-4 rad about the x axis, its near edge 1e-5 below the small square's plane: its
  // front half-space leaves a sliver of the small square, and vice versa.
  const double t = 1e-4;
  const Polygon large = {Vec3(-5, 3, -1e-5), Vec3(5, 3, -1e-5), Vec3(5, 3 + 10 * std::cos(t), -1e-5 + 10 * std::sin(t)),
                         Vec3(-5, 3 + 10 * std::cos(t), -1e-5 + 10 * std::sin(t))};
  const double a_small = 1.0;
  for (const auto& [from, to] : {std::pair{small, large}, std::pair{large, small}}) {
    const PairFormFactor exact = polygon_to_polygon(from, to);
    const PairFormFactor fast = polygon_to_polygon(from, to, 1e-7, 1e-9);
    const double area_from = polygon_area(from);
    EXPECT_NEAR(fast.from_to * area_from, exact.from_to * area_from, 1e-9 * a_small);
    EXPECT_GE(fast.from_to, 0.0);
  }
}

}  // namespace
}  // namespace hrad::test
