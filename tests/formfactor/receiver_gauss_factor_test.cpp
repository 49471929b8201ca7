// receiver_gauss_factor(): the solvers' Gauss-point kernel against Howell's closed forms and the
// analytic kernel, and its closure (each point's factors to a closed surface sum to 1).
#include <cmath>

#include <gtest/gtest.h>

#include "howell.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/formfactor/receiver_gauss_factor.h"
#include "hrad/geometry/polygon.h"
#include "test_geometry.h"

namespace hrad::test {
namespace {

TEST(ReceiverGaussFactor, ConvergesToHowellC11WithDistance) {
  // Parallel opposed unit squares at distance c (C-11). The 3 x 3 rule integrates a degree-5
  // polynomial exactly; the integrand's variation over the receiver falls with distance, so the
  // error falls fast: ~1e-4 at c = 1, far below at c = 4.
  const Polygon a = rectangle(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY());
  for (const auto& [c, bound] : {std::pair{1.0, 1e-3}, {4.0, 1e-6}, {16.0, 1e-9}}) {
    const Polygon b = reversed(rectangle(Vec3(0, 0, c), Vec3::UnitX(), Vec3::UnitY()));
    EXPECT_LE(relative_error(receiver_gauss_factor(a, b), howell_c11(1.0, 1.0, c)), bound) << c;
  }
}

TEST(ReceiverGaussFactor, TriangleAndPentagonReceiversAgreeWithTheAnalyticKernel) {
  const Polygon b = reversed(rectangle(Vec3(0, 0, 1.5), Vec3::UnitX(), Vec3::UnitY()));
  const Polygon triangle = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  const Polygon pentagon = {{0, 0, 0}, {1, 0, 0}, {1.2, 0.6, 0}, {0.5, 1.1, 0}, {-0.2, 0.6, 0}};
  for (const Polygon& p : {triangle, pentagon})
    EXPECT_LE(relative_error(receiver_gauss_factor(p, b), polygon_to_polygon(p, b).from_to), 1e-3) << p.size();
}

// The contour kernel keeps this rule for a source floating in front of the receiver no closer than
// the receiver's diameter D and takes the closed form nearer (FormFactorKernel::kPointContour): at
// height D the rule is within 1e-3 (measured 2.5e-4 at most), at D / 4 a source a quarter of the
// receiver's size is off by more than 5% (the control: the near field the closed form is for).
TEST(ReceiverGaussFactor, FloatingSourceIsWithin1e3DownToTheReceiversDiameter) {
  const Polygon receiver = rectangle(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY());
  const double d = std::sqrt(2.0);
  for (const double side : {1.0, 0.25})
    for (const double offset : {0.0, 0.3}) {
      const Vec3 corner(0.5 - side / 2 + offset, 0.5 - side / 2 + 0.7 * offset, 0.0);
      auto source = [&](double h) {
        return reversed(rectangle(corner + Vec3(0, 0, h), side * Vec3::UnitX(), side * Vec3::UnitY()));
      };
      for (const double ratio : {0.5, 1.0}) {
        const Polygon s = source(d / ratio);
        EXPECT_LE(relative_error(receiver_gauss_factor(receiver, s), polygon_to_polygon(receiver, s).from_to), 1e-3)
            << side << " " << offset << " D/h " << ratio;
      }
      if (side < 1.0) {
        const Polygon s = source(d / 4.0);
        EXPECT_GT(relative_error(receiver_gauss_factor(receiver, s), polygon_to_polygon(receiver, s).from_to), 0.05)
            << offset;
      }
    }
}

TEST(ReceiverGaussFactor, PointWeightsSumToTheArea) {
  std::vector<detail::WeightedPoint> points;
  const Polygon quad = {{0, 0, 0}, {2, 0, 0}, {2.5, 1, 0}, {0, 1.5, 0}};
  const Polygon pentagon = {{0, 0, 0}, {1, 0, 0}, {1.2, 0.6, 0}, {0.5, 1.1, 0}, {-0.2, 0.6, 0}};
  for (const Polygon& p : {quad, pentagon}) {
    receiver_gauss_points(p, Vec3::UnitZ(), points);
    double sum = 0.0;
    for (const auto& w : points) sum += w.weight;
    EXPECT_NEAR(sum, polygon_area(p), 1e-14 * polygon_area(p)) << p.size();
  }
}

TEST(ReceiverGaussFactor, ClosureInABoxWithTJunctions) {
  // An element of the floor of a 1 x 2 x 0.7 box against the other five faces, each split into a
  // different grid: the factors sum to 1 to rounding, whatever the rule's own error.
  const Vec3 x(1, 0, 0), y(0, 2, 0), z(0, 0, 0.7);
  std::vector<Polygon> others;
  auto split = [&](const Vec3& o, const Vec3& u, const Vec3& v, int n, int m) {
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j)
        others.push_back(rectangle(o + (double(i) / n) * u + (double(j) / m) * v, u / n, v / m));
  };
  split(z, y, x, 2, 5);             // ceiling, -z
  split(Vec3::Zero(), z, x, 1, 3);  // y = 0, +y
  split(y, x, z, 4, 1);             // y = Ly, -y
  split(Vec3::Zero(), y, z, 2, 2);  // x = 0, +x
  split(x, z, y, 3, 3);             // x = Lx, -x
  for (const Polygon& element :
       {rectangle(Vec3(0.2, 0.1, 0), 0.3 * x, 0.2 * y), Polygon{{0, 0, 0}, {0.4, 0.1, 0}, {0.1, 0.5, 0}}}) {
    double sum = 0.0;
    for (const Polygon& o : others) sum += receiver_gauss_factor(element, o);
    EXPECT_NEAR(sum, 1.0, 1e-12) << element.size();
  }
}

TEST(ReceiverFactorByDistance, CentroidRuleErrorStaysBelowTheQuarterSquaredRatio) {
  // Small square receivers, tilted and offset, against a unit square: where the one-point rule is
  // taken, it is within (diameter / gap)^2 / 4 of the 3 x 3 rule (whose own error is far below,
  // see ConvergesToHowellC11WithDistance); near ones take the 3 x 3 rule itself, to the bit.
  const Polygon source = reversed(rectangle(Vec3(0, 0, 3), Vec3::UnitX(), Vec3::UnitY()));
  int centroid = 0, gauss = 0;
  for (const double side : {0.05, 0.2, 0.6})
    for (const double offset : {0.0, 1.5, 3.0})
      for (const double tilt : {0.0, 0.5}) {
        const Vec3 u = side * Vec3(std::cos(tilt), 0, std::sin(tilt)), v = side * Vec3::UnitY();
        const Polygon receiver = rectangle(Vec3(offset, 0.3, 0), u, v);
        const double exact = receiver_gauss_factor(receiver, source);
        const double f = receiver_factor_by_distance(receiver, source, 0.1);
        const double gap =
            (polygon_centroid(receiver) - polygon_centroid(source)).norm() - 0.5 * (u + v).norm() - std::sqrt(0.5);
        const double ratio = (u + v).norm() / gap;
        if (ratio <= 0.1) {
          ++centroid;
          EXPECT_LE(relative_error(f, exact), 0.25 * ratio * ratio) << side << " " << offset << " " << tilt;
          EXPECT_GT(relative_error(f, exact), 0.0);  // it is the other rule
        } else {
          ++gauss;
          EXPECT_EQ(f, exact) << side << " " << offset << " " << tilt;
        }
      }
  EXPECT_GT(centroid, 0);
  EXPECT_GT(gauss, 0);
}

}  // namespace
}  // namespace hrad::test
