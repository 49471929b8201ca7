// Exact from-point visibility (2D Boolean operations) against closed forms, and sampled
// visibility converging to it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/visibility/occluded_form_factor.h"
#include "hrad/visibility/visibility.h"
#include "hrad/visibility/visible_region.h"
#include "test_scenes.h"

namespace hrad {
namespace {

using test::add_patch;
using test::empty_scene;
using test::square_z;

const std::vector<Vec3> kSource = square_z(0, 1, 0, 1, 0, true);
const Vec3 kEye(0.5, 0.5, 2.0);

double ring_area(const std::vector<Vec3>& ring) {  // signed, seen from +z
  double a = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec3& p = ring[i];
    const Vec3& q = ring[(i + 1) % ring.size()];
    a += 0.5 * (p.x() * q.y() - q.x() * p.y());
  }
  return a;
}

TEST(VisibleRegion, ParallelOccluderCastsTheScaledSquare) {
  // Occluder [3/8, 5/8]^2 at z = 1, half way to the eye at z = 2: its shadow is [1/4, 3/4]^2.
  // (Dyadic coordinates, so that the exact answer is a double.)
  Scene s = empty_scene();
  const int src = add_patch(s, kSource);
  add_patch(s, square_z(0.375, 0.625, 0.375, 0.625, 1, false));
  const VisibleRegion r = visible_region(s, kEye, -1, kSource, src);
  EXPECT_EQ(r.area_fraction, 0.75);  // 1 - (1/2)^2
  ASSERT_EQ(r.pieces.size(), 1u);
  ASSERT_EQ(r.pieces[0].holes.size(), 1u);
  EXPECT_NEAR(ring_area(r.pieces[0].outer), 1.0, 1e-15);  // counter-clockwise from the front
  EXPECT_EQ(ring_area(r.pieces[0].holes[0]), -0.25);      // clockwise
  for (const Vec3& p : r.pieces[0].holes[0]) {
    EXPECT_EQ(std::abs(p.x() - 0.5), 0.25);
    EXPECT_EQ(std::abs(p.y() - 0.5), 0.25);
    EXPECT_EQ(p.z(), 0.0);
  }
}

TEST(VisibleRegion, OnlyThePartInsideThePyramidCounts) {
  Scene s = empty_scene();
  const int src = add_patch(s, kSource);
  add_patch(s, square_z(0.625, 1.5, 0.375, 0.625, 1, false));  // shadow [0.75, 1] x [0.25, 0.75]: 1/8
  add_patch(s, square_z(-3, 3, -3, 3, -1, true));              // behind the source
  add_patch(s, square_z(-3, 3, -3, 3, 3, false));              // behind the eye
  add_patch(s, square_z(-3, 3, -3, 3, 0, true));               // coplanar with the source (touches it)
  add_patch(s, {{0.5, -1, 2}, {0.5, 2, 2}, {0.5, 0.5, 2.5}});  // through the eye: projects to a line
  const VisibleRegion r = visible_region(s, kEye, -1, kSource, src);
  EXPECT_EQ(r.area_fraction, 0.875);
}

TEST(VisibleRegion, OccluderCrossingTheSourcePlaneCountsAboveIt) {
  // A wall x = 0.5 from z = -1 to z = 1 seen from (0.25, 0.5, 2): only its part above the
  // source's plane casts a shadow, from x = 0.5 (its foot) to 0.25 + 0.25 * 2 / (2 - 1) = 0.75.
  Scene s = empty_scene();
  const int src = add_patch(s, kSource);
  add_patch(s, {{0.5, -1, -1}, {0.5, -1, 1}, {0.5, 2, 1}, {0.5, 2, -1}});
  const VisibleRegion r = visible_region(s, {0.25, 0.5, 2.0}, -1, kSource, src);
  EXPECT_EQ(r.area_fraction, 0.75);  // hidden: [0.5, 0.75] x [0, 1]
}

TEST(VisibleRegion, NothingIsVisibleFromBehind) {
  Scene s = empty_scene();
  const int src = add_patch(s, kSource);
  EXPECT_EQ(visible_region(s, {0.5, 0.5, -1}, -1, kSource, src).area_fraction, 0.0);
  EXPECT_TRUE(visible_region(s, {0.5, 0.5, 0}, -1, kSource, src).pieces.empty());
}

TEST(OccludedPointToPolygon, EqualsSourceMinusShadowFactor) {
  Scene s = empty_scene();
  const int src = add_patch(s, kSource);
  add_patch(s, square_z(0.375, 0.625, 0.375, 0.625, 1, false));
  const Vec3 n(0.3, -0.2, -1.0);
  const double expected = point_to_polygon(kEye, n.normalized(), kSource) -
                          point_to_polygon(kEye, n.normalized(), square_z(0.25, 0.75, 0.25, 0.75, 0, true));
  EXPECT_NEAR(occluded_point_to_polygon(s, kEye, n.normalized(), -1, kSource, src), expected, 1e-14);
  // Without occluders it is the plain factor.
  Scene bare = empty_scene();
  add_patch(bare, kSource);
  EXPECT_NEAR(occluded_point_to_polygon(bare, kEye, n.normalized(), -1, kSource, 0),
              point_to_polygon(kEye, n.normalized(), kSource), 1e-15);
}

/// A source with random occluder triangles between it and an eye.
Scene random_occluders(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Scene s = empty_scene();
  add_patch(s, kSource);
  for (int i = 0; i < count; ++i) {
    const Vec3 c(u(rng), u(rng), 0.2 + 1.5 * u(rng));
    const double r = 0.15 + 0.35 * u(rng);
    add_patch(s, {c + r * Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * 2,
                  c + r * Vec3(u(rng), -u(rng), u(rng) - 0.5), c + r * Vec3(-u(rng), u(rng), u(rng) - 0.5)});
  }
  return s;
}

TEST(SampledVisibility, ConvergesToTheExactFromPointReference) {
  const Scene s = random_occluders(3, 12);
  const auto v = make_visibility(s);
  const Vec3 eye(0.4, 0.6, 2.0);
  const double exact = visible_region(s, eye, -1, kSource, 0).area_fraction;
  ASSERT_GT(exact, 0.2);
  ASSERT_LT(exact, 0.95);
  double mean_error[3] = {0, 0, 0};
  const int sizes[3] = {64, 1024, 16384};
  const int seeds = 12;
  for (int k = 0; k < 3; ++k)
    for (int seed = 0; seed < seeds; ++seed) {
      const VisibilityEstimate e = v->estimate_from_point(eye, -1, kSource, 0, sizes[k], seed);
      ASSERT_EQ(e.pair_class, PairClass::kPartial);
      const double err = std::abs(e.fraction - exact);
      // Each estimate lies within four of its own error estimates (plus one sample's worth).
      EXPECT_LE(err, 4.0 * e.error + 1.0 / sizes[k]) << sizes[k] << " " << seed;
      mean_error[k] += err / seeds;
    }
  // Stratified sampling of a region with straight edges converges like n^(-3/4); demand at least
  // n^(-1/2) between each size (a factor 4 for 16x the samples) and a small final error.
  EXPECT_LT(mean_error[1], mean_error[0] / 4.0);
  EXPECT_LT(mean_error[2], mean_error[1] / 4.0);
  EXPECT_LT(mean_error[2], 2e-3);
}

TEST(SampledVisibility, FormFactorWithSampledVisibilityMatchesTheExactOccludedFactor) {
  // Monte Carlo F = A/N sum cos_x cos_y V / (pi r^2) over uniform points y of the source: an
  // estimator independent of the 2D Boolean code.
  const Scene s = random_occluders(8, 30);
  const auto v = make_visibility(s);
  const Vec3 eye(0.55, 0.45, 1.9);
  const Vec3 n = Vec3(0.2, 0.1, -1).normalized();
  const double exact = occluded_point_to_polygon(s, eye, n, -1, kSource, 0);
  const double bare = point_to_polygon(eye, n, kSource);
  ASSERT_LT(exact, 0.9 * bare);  // the occluders matter
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  const int count = 40000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < count; ++i) {
    const Vec3 y(u(rng), u(rng), 0.0);
    const Vec3 d = y - eye;
    const double r2 = d.squaredNorm();
    const double g = std::max(0.0, n.dot(d)) * std::max(0.0, -d.z()) / (std::numbers::pi * r2 * r2);
    const double f = v->segment_blocked(eye, -1, y, 0) ? 0.0 : g;
    sum += f;
    sum2 += f * f;
  }
  const double mean = sum / count, sigma = std::sqrt((sum2 / count - mean * mean) / count);
  EXPECT_NEAR(mean, exact, 4 * sigma);
  EXPECT_LT(sigma, 0.01 * exact);
}

TEST(SampledVisibility, PairVisibilityConvergesToTheMidplaneClosedForm) {
  // Unit squares at z = 0 and z = 1, occluder [1/2 - h, 1/2 + h]^2 at z = 1/2: a segment meets the
  // midplane at the mean of its ends, whose coordinates are each the mean of two uniforms
  // (triangular density on [0, 1]); P(|m - 1/2| < h) = 1 - (1 - 2h)^2, so the visible fraction is
  // 1 - (1 - (1 - 2h)^2)^2. With h = 1/4: 1 - (3/4)^2 = 0.4375.
  Scene s = empty_scene();
  const auto ceiling = square_z(0, 1, 0, 1, 1, false);
  const int a = add_patch(s, kSource), b = add_patch(s, ceiling);
  add_patch(s, square_z(0.25, 0.75, 0.25, 0.75, 0.5, true));
  const auto v = make_visibility(s);
  const double exact = 0.4375;
  double mean_abs = 0.0;
  for (int seed = 0; seed < 10; ++seed) {
    const VisibilityEstimate e = v->estimate(kSource, a, ceiling, b, 4096, seed);
    EXPECT_LE(std::abs(e.fraction - exact), 4 * e.error);
    mean_abs += std::abs(e.fraction - exact) / 10;
  }
  EXPECT_LT(mean_abs, 0.01);
}

}  // namespace
}  // namespace hrad
