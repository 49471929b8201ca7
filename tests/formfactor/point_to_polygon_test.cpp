// Differential element to polygon against Howell's closed forms (B-3 and the perpendicular element),
// over aspect ratios and distances 1e-3..1e3, plus the cases that must be exactly 0.
#include "hrad/formfactor/point_to_polygon.h"

#include <gtest/gtest.h>

#include <numbers>

#include "howell.h"
#include "test_geometry.h"

namespace hrad::test {
namespace {

const double kRatios[] = {1e-3, 0.01, 0.3, 1.0, 2.5, 30.0, 1e3};

TEST(PointToPolygon, ParallelRectangleHowellB3) {
  // Element at the origin looking up (+z); rectangle a x b at height c with a corner above it,
  // counter-clockwise seen from below (its front faces the element).
  for (double a : kRatios)
    for (double b : kRatios)
      for (double c : {1e-3, 0.1, 1.0, 10.0, 1e3}) {
        const Polygon r = rectangle(Vec3(0, 0, c), Vec3(0, b, 0), Vec3(a, 0, 0));
        const double exact = howell_b3(a, b, c);
        EXPECT_LE(relative_error(point_to_polygon(Vec3::Zero(), Vec3::UnitZ(), r), exact), exact > 1e-12 ? 1e-11 : 1e-8)
            << "a=" << a << " b=" << b << " c=" << c;
      }
}

TEST(PointToPolygon, PerpendicularRectangleHowell) {
  // Rectangle in the plane y = c, x in [0, a], z in [0, b], facing -y (towards the element).
  for (double a : kRatios)
    for (double b : kRatios)
      for (double c : {1e-3, 0.1, 1.0, 10.0, 1e3}) {
        const Polygon r = rectangle(Vec3(0, c, 0), Vec3(a, 0, 0), Vec3(0, 0, b));
        const double exact = howell_perpendicular_element(a, b, c);
        EXPECT_LE(relative_error(point_to_polygon(Vec3::Zero(), Vec3::UnitZ(), r), exact), exact > 1e-12 ? 1e-11 : 1e-8)
            << "a=" << a << " b=" << b << " c=" << c << " F=" << exact;
      }
}

TEST(PointToPolygon, PerpendicularFormulaAgreesWithKernelQuadrature) {
  // Checks the reference formula itself: tensor midpoint rule of cos1 cos2 / (pi r^2), Richardson-free
  // but fine (the kernel is smooth here: the rectangle is 1 away from the element).
  const double a = 1.3, b = 0.7, c = 1.0;
  const int n = 400;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3 y((i + 0.5) * a / n, c, (j + 0.5) * b / n);
      const double r2 = y.squaredNorm();
      sum += y.z() * y.y() / (std::numbers::pi * r2 * r2);
    }
  EXPECT_NEAR(sum * (a / n) * (b / n), howell_perpendicular_element(a, b, c), 2e-6);
}

TEST(PointToPolygon, SplitPolygonsAddUp) {
  // Skew edges: the rectangle cut along a diagonal and rotated/moved with the element.
  std::mt19937_64 rng(7);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Matrix3d rot = random_rotation(rng);
    const Vec3 shift(3.0 * k, -1.0, 2.0);
    const Polygon r = rectangle(Vec3(0, 0, 1.0), Vec3(0, 2.0, 0), Vec3(0.5, 0, 0));
    const Polygon t1 = moved({r[0], r[1], r[2]}, rot, shift), t2 = moved({r[0], r[2], r[3]}, rot, shift);
    const Vec3 x = shift, n = rot * Vec3::UnitZ();
    const double exact = howell_b3(0.5, 2.0, 1.0);
    EXPECT_LE(relative_error(point_to_polygon(x, n, t1) + point_to_polygon(x, n, t2), exact), 1e-12);
  }
}

TEST(PointToPolygon, ClippedToTheTangentHalfSpace) {
  // A wall straddling the element's plane: only its upper part (z in [0, b]) counts.
  const double a = 1.0, b = 0.8, c = 0.6;
  const Polygon wall = rectangle(Vec3(0, c, -5.0), Vec3(a, 0, 0), Vec3(0, 0, b + 5.0));
  EXPECT_LE(relative_error(point_to_polygon(Vec3::Zero(), Vec3::UnitZ(), wall), howell_perpendicular_element(a, b, c)),
            1e-12);
}

TEST(PointToPolygon, ExactZeros) {
  const Polygon above = rectangle(Vec3(0, 0, 1), Vec3(0, 1, 0), Vec3(1, 0, 0));  // faces down
  // Element facing away.
  EXPECT_EQ(point_to_polygon(Vec3::Zero(), -Vec3::UnitZ(), above), 0.0);
  // Polygon facing away (its back towards the element).
  EXPECT_EQ(point_to_polygon(Vec3::Zero(), Vec3::UnitZ(), reversed(above)), 0.0);
  // Element in the polygon's plane.
  EXPECT_EQ(point_to_polygon(Vec3(3, 0, 1), Vec3::UnitZ(), above), 0.0);
  EXPECT_EQ(point_to_polygon(Vec3(3, 0, 1), -Vec3::UnitX(), above), 0.0);
  // Polygon in the element's tangent plane, or below it.
  const Polygon floor = rectangle(Vec3(1, 1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  EXPECT_EQ(point_to_polygon(Vec3::Zero(), Vec3::UnitZ(), floor), 0.0);
  EXPECT_EQ(point_to_polygon(Vec3(0, 0, 2), Vec3::UnitZ(), above), 0.0);
  // Degenerate input.
  EXPECT_EQ(point_to_polygon(Vec3::Zero(), Vec3::UnitZ(), Polygon{Vec3(0, 0, 1), Vec3(1, 0, 1)}), 0.0);
}

TEST(PointToPolygon, UnitIndependent) {
  const Polygon r = rectangle(Vec3(0.2, -0.1, 0.7), Vec3(0, 1.3, 0.1), Vec3(0.9, 0, 0));
  const Vec3 x(0.1, 0.2, 0.0), n = Vec3(0.1, -0.2, 1.0).normalized();
  const double reference = point_to_polygon(x, n, r);
  ASSERT_GT(reference, 0.01);
  for (double s : {1e-8, 1e-4, 1e4, 1e8}) {
    const Polygon rs = moved(r, Eigen::Matrix3d::Identity(), Vec3(1, 2, 3) * s, s);
    EXPECT_LE(relative_error(point_to_polygon(s * x + Vec3(1, 2, 3) * s, n, rs), reference), 1e-13) << s;
  }
}

}  // namespace
}  // namespace hrad::test
