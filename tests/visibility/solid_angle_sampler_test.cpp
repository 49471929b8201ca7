// Sampling of polygons by solid angle (visibility/solid_angle_sampler.h) against closed forms:
// the solid angle of a rectangle seen from above its corner, the shares of its parts, and the
// point-to-polygon factor (Lambert's contour formula) as the cosine-weighted mean.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "hrad/core/rng.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/visibility/sampling.h"
#include "hrad/visibility/solid_angle_sampler.h"

namespace hrad {
namespace {

// Solid angle of the rectangle [0, a] x [0, b] seen from the height d above its corner (0, 0).
double corner_solid_angle(double a, double b, double d) {
  return std::atan(a * b / (d * std::sqrt(a * a + b * b + d * d)));
}

const std::vector<Vec3> kRect{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};  // front +z

TEST(SolidAngleSampler, SolidAngleOfARectangleFromAboveItsCorner) {
  for (const double d : {1e-4, 1e-2, 0.3, 1.0, 30.0}) {
    const detail::SolidAngleSampler s(Vec3(0, 0, d), kRect);
    EXPECT_NEAR(s.solid_angle(), corner_solid_angle(2, 1, d), 1e-13 * corner_solid_angle(2, 1, d)) << d;
  }
  // In the rectangle's plane it is seen edge-on; behind it, the same solid angle.
  EXPECT_EQ(detail::SolidAngleSampler(Vec3(3, 0.5, 0), kRect).solid_angle(), 0.0);
  EXPECT_NEAR(detail::SolidAngleSampler(Vec3(0, 0, -0.3), kRect).solid_angle(), corner_solid_angle(2, 1, 0.3), 1e-14);
}

TEST(SolidAngleSampler, PointsLieOnThePolygonUniformlyInSolidAngle) {
  // From a hundredth above the corner most of the solid angle is near the corner: area-uniform
  // points would put 1/2 of them at x < 1 and 1/2 at y < 1/2; by solid angle the shares are the
  // corner rectangles' solid angles over the whole's. 40,000 stratified points, 5 standard errors.
  for (const double d : {0.01, 0.5}) {
    const Vec3 x(0, 0, d);
    const detail::SolidAngleSampler s(x, kRect);
    const double whole = corner_solid_angle(2, 1, d);
    const double left = corner_solid_angle(1, 1, d) / whole, low = corner_solid_angle(2, 0.5, d) / whole;
    detail::Rng rng(5);
    std::vector<Vec2> uv;
    const int n = 40000;
    detail::stratified_unit_square(n, rng, &uv);
    int in_left = 0, in_low = 0;
    for (const Vec2& u : uv) {
      Vec3 direction, p;
      ASSERT_TRUE(s.sample(u.x(), u.y(), &direction, &p));
      ASSERT_NEAR(direction.norm(), 1.0, 1e-14);
      ASSERT_NEAR((p - x).normalized().dot(direction), 1.0, 1e-14);
      ASSERT_NEAR(p.z(), 0.0, 1e-15);
      ASSERT_GE(p.x(), -1e-12);
      ASSERT_LE(p.x(), 2 + 1e-12);
      ASSERT_GE(p.y(), -1e-12);
      ASSERT_LE(p.y(), 1 + 1e-12);
      in_left += p.x() < 1.0;
      in_low += p.y() < 0.5;
    }
    EXPECT_NEAR(double(in_left) / n, left, 5 * std::sqrt(left * (1 - left) / n)) << d;
    EXPECT_NEAR(double(in_low) / n, low, 5 * std::sqrt(low * (1 - low) / n)) << d;
    if (d < 0.1) EXPECT_GT(left, 0.7);  // far from area-uniform's 1/2: the test tells them apart
  }
}

TEST(SolidAngleSampler, CosineWeightedMeanIsThePointFactor) {
  // F(dA_x -> P) = (1/pi) integral over P's solid angle of cos(theta_x): (Omega / pi) times the
  // mean cosine of uniform directions. Points a millimetre from a tilted pentagon, beside its edge
  // (a board beside an upright) and far; tilted normals.
  const Vec3 origin(0.3, -1, 2), u(0.8, 0.6, 0), v(-0.36, 0.48, 0.8);  // u, v orthonormal
  std::vector<Vec3> pentagon;
  for (const auto& [a, b] : {std::pair{0.0, 0.0}, {1.4, 0.2}, {1.6, 1.1}, {0.6, 1.7}, {-0.3, 0.9}})
    pentagon.push_back(origin + a * u + b * v);
  const Vec3 plane_normal = (pentagon[1] - pentagon[0]).cross(pentagon[2] - pentagon[0]).normalized();
  const Vec3 inside = (pentagon[0] + pentagon[2]) / 2;
  const Vec3 edge_mid = (pentagon[0] + pentagon[1]) / 2;
  const Vec3 outward = (edge_mid - inside).normalized();
  struct Case {
    Vec3 x, n;
  };
  const std::vector<Case> cases{
      {inside + 1e-3 * plane_normal, (-plane_normal + Vec3(0.3, 0.1, 0)).normalized()},
      {edge_mid + 5e-3 * outward + 1e-3 * plane_normal, (-outward - 0.2 * plane_normal).normalized()},
      {inside + 4.0 * plane_normal, (-plane_normal + Vec3(0, 0.2, 0.1)).normalized()},
  };
  for (const Case& c : cases) {
    const detail::SolidAngleSampler s(c.x, pentagon);
    detail::Rng rng(9);
    const int n = 20000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      Vec3 direction, p;
      ASSERT_TRUE(s.sample(rng.uniform(), rng.uniform(), &direction, &p));
      const double f = s.solid_angle() / std::numbers::pi * std::max(0.0, c.n.dot(direction));
      sum += f, sum2 += f * f;
    }
    const double mean = sum / n, sigma = std::sqrt((sum2 / n - mean * mean) / n);
    const double exact = point_to_polygon(c.x, c.n, pentagon);
    ASSERT_GT(exact, 0.0);
    EXPECT_NEAR(mean, exact, 5 * sigma) << c.x.transpose();
    EXPECT_LT(sigma, 0.01 * exact);
  }
}

}  // namespace
}  // namespace hrad
