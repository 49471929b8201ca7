// Sampling of polygons (visibility/sampling.h): points uniform by area, the allocation-free
// polygon_point() bit for bit the sampler's.
#include <gtest/gtest.h>

#include <vector>

#include "hrad/visibility/sampling.h"

namespace hrad {
namespace {

std::vector<std::vector<Vec3>> polygons() {
  return {
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
      {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}},
      {{0.3, -1, 2}, {1.7, -0.2, 2.5}, {1.1, 0.9, 2.8}, {-0.4, 0.7, 2.1}, {-0.8, -0.5, 1.9}},  // convex pentagon
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}},  // a repeated vertex: a zero-area fan triangle
      {{5, 5, 5}, {5, 5, 5}, {5, 5, 5}},             // degenerate: every point is the vertex
  };
}

TEST(PolygonPoint, SameBitsAsTheSampler) {
  detail::Rng rng(11);
  for (const std::vector<Vec3>& p : polygons()) {
    const detail::PolygonSampler sampler(p);
    for (int i = 0; i < 2000; ++i) {
      // The ends of [0, 1] and the fan's cumulative shares are where an off-by-one would show.
      const double u = i < 3 ? 0.5 * i : rng.uniform(), v = i < 3 ? 0.5 * i : rng.uniform();
      const Vec3 a = sampler.point(u, v), b = detail::polygon_point(p, u, v);
      ASSERT_EQ(a.x(), b.x()) << "u " << u << " v " << v;
      ASSERT_EQ(a.y(), b.y());
      ASSERT_EQ(a.z(), b.z());
    }
  }
}

TEST(PolygonPoint, UniformByArea) {
  // The 2 x 1 rectangle split by the fan into two triangles of equal area: each half of x gets half
  // the points, and the mean is the centroid (1, 0.5); 40,000 points, 5 standard errors.
  const std::vector<Vec3> rect{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  detail::Rng rng(3);
  const int n = 40000;
  double sx = 0.0, sy = 0.0;
  int left = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 x = detail::polygon_point(rect, rng.uniform(), rng.uniform());
    sx += x.x(), sy += x.y();
    left += x.x() < 1.0;
  }
  EXPECT_NEAR(sx / n, 1.0, 5 * 0.577 / 200.0);  // sd of x uniform on [0, 2]: 2 / sqrt(12)
  EXPECT_NEAR(sy / n, 0.5, 5 * 0.289 / 200.0);
  EXPECT_NEAR(double(left) / n, 0.5, 5 * 0.5 / 200.0);
}

}  // namespace
}  // namespace hrad
