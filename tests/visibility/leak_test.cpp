// Leak tests: a closed box of zero-thickness walls, each wall tessellated independently into
// triangles (T-junctions along every edge), lit only from outside. No light may get in.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "hrad/visibility/visibility.h"
#include "test_scenes.h"

namespace hrad {
namespace {

using test::add_patch;
using test::empty_scene;

constexpr double kSize[3] = {0.7, 1.3, 0.9};  // box [0, 0.7] x [0, 1.3] x [0, 0.9]

/// Sorted grid coordinates on [0, length]: exact ends, random interior points (so the vertices
/// of neighbouring walls along a shared edge do not match).
std::vector<double> edge_coordinates(int cells, double length, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, length);
  std::vector<double> c{0.0, length};
  while (static_cast<int>(c.size()) < cells + 1) {
    const double x = u(rng);
    if (std::none_of(c.begin(), c.end(), [&](double y) { return std::abs(x - y) < 0.02 * length; })) c.push_back(x);
  }
  std::sort(c.begin(), c.end());
  return c;
}

/// Adds one wall of the box: the face where axis `axis` is 0 (`high` false) or kSize[axis],
/// front facing into the box, as a jittered grid of triangles with random diagonals.
/// Returns the indices of its patches.
std::vector<int> add_wall(Scene& s, int axis, bool high, int cells_u, int cells_v, std::mt19937_64& rng) {
  const int au = (axis + 1) % 3, av = (axis + 2) % 3;
  const std::vector<double> cu = edge_coordinates(cells_u, kSize[au], rng);
  const std::vector<double> cv = edge_coordinates(cells_v, kSize[av], rng);
  std::uniform_real_distribution<double> jitter(-0.25, 0.25);
  // Grid of vertices; interior ones jittered within the wall's plane (boundary ones stay on the
  // box's edges so the walls close exactly).
  std::vector<std::vector<Vec3>> grid(cu.size(), std::vector<Vec3>(cv.size()));
  for (std::size_t i = 0; i < cu.size(); ++i)
    for (std::size_t j = 0; j < cv.size(); ++j) {
      double u = cu[i], v = cv[j];
      if (i > 0 && i + 1 < cu.size() && j > 0 && j + 1 < cv.size()) {
        u += jitter(rng) * std::min(cu[i] - cu[i - 1], cu[i + 1] - cu[i]);
        v += jitter(rng) * std::min(cv[j] - cv[j - 1], cv[j + 1] - cv[j]);
      }
      Vec3 p;
      p[axis] = high ? kSize[axis] : 0.0;
      p[au] = u;
      p[av] = v;
      grid[i][j] = p;
    }
  // (u, v, axis) is right-handed, so counter-clockwise in (u, v) faces +axis: inward on the low wall.
  std::vector<int> ids;
  std::bernoulli_distribution coin(0.5);
  auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    ids.push_back(high ? add_patch(s, {a, c, b}) : add_patch(s, {a, b, c}));
  };
  for (std::size_t i = 0; i + 1 < cu.size(); ++i)
    for (std::size_t j = 0; j + 1 < cv.size(); ++j) {
      const Vec3 &p00 = grid[i][j], &p10 = grid[i + 1][j], &p11 = grid[i + 1][j + 1], &p01 = grid[i][j + 1];
      if (coin(rng)) {
        tri(p00, p10, p11);
        tri(p00, p11, p01);
      } else {
        tri(p00, p10, p01);
        tri(p10, p11, p01);
      }
    }
  return ids;
}

struct LeakBox {
  Scene scene;
  std::vector<int> inside;    ///< the box's wall triangles (fronts inside)
  std::vector<int> emitters;  ///< quads outside, facing the box
};

LeakBox make_leak_box(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  LeakBox b;
  b.scene = empty_scene();
  const int cells[6][2] = {{3, 4}, {5, 2}, {4, 3}, {2, 5}, {6, 3}, {3, 6}};
  for (int axis = 0; axis < 3; ++axis)
    for (int high = 0; high < 2; ++high) {
      const auto ids = add_wall(b.scene, axis, high == 1, cells[2 * axis + high][0], cells[2 * axis + high][1], rng);
      b.inside.insert(b.inside.end(), ids.begin(), ids.end());
    }
  // Emitters outside: one left of the box facing +x, one above facing -z, one diagonal.
  b.emitters.push_back(
      add_patch(b.scene, {{-0.5, -0.2, -0.2}, {-0.5, 1.5, -0.2}, {-0.5, 1.5, 1.1}, {-0.5, -0.2, 1.1}}));
  b.emitters.push_back(add_patch(b.scene, {{-0.2, -0.2, 1.6}, {-0.2, 1.5, 1.6}, {0.9, 1.5, 1.6}, {0.9, -0.2, 1.6}}));
  b.emitters.push_back(add_patch(b.scene, {{1.5, 1.9, 1.4}, {1.5, 2.4, 1.4}, {1.2, 2.4, 1.9}}));
  return b;
}

TEST(Leak, EverySegmentFromOutsideToInsideIsBlocked) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const LeakBox box = make_leak_box(seed);
    const auto v = make_visibility(box.scene);
    std::mt19937_64 rng(seed * 31);
    std::uniform_real_distribution<double> u(0, 1);
    auto inside_point = [&] { return Vec3(u(rng) * kSize[0], u(rng) * kSize[1], u(rng) * kSize[2]); };
    for (int e : box.emitters) {
      const auto& q = box.scene.patches[e].vertices;
      for (int i = 0; i < 3000; ++i) {
        // A point on the emitter (vertices included) to a point inside the box.
        const Vec3 from =
            i < static_cast<int>(q.size()) ? q[i] : q[0] + u(rng) * (q[1] - q[0]) + u(rng) * (q.back() - q[0]) * 0.5;
        ASSERT_TRUE(v->segment_blocked(from, e, inside_point(), -1)) << "seed " << seed;
      }
    }
    // Segments aimed exactly at the box's corners and at wall vertices (the T-junctions), ending
    // at the box's centre.
    const Vec3 centre(0.5 * kSize[0], 0.5 * kSize[1], 0.5 * kSize[2]);
    for (int p : box.inside)
      for (const Vec3& x : box.scene.patches[p].vertices) {
        const Vec3 outside = centre + 3.0 * (x - centre);
        ASSERT_TRUE(v->segment_blocked(outside, -1, centre, -1)) << "seed " << seed;
      }
  }
}

TEST(Leak, SampledVisibilityFromOutsideToEveryInsideElementIsExactlyZero) {
  const LeakBox box = make_leak_box(4);
  const auto v = make_visibility(box.scene);
  int needed_occlusion = 0;
  for (int e : box.emitters)
    for (int p : box.inside) {
      const VisibilityEstimate est = v->estimate(box.scene.patches[e].vertices, e, box.scene.patches[p].vertices, p, 64,
                                                 static_cast<std::uint64_t>(p));
      ASSERT_EQ(est.fraction, 0.0) << "emitter " << e << " element " << p;
      needed_occlusion += est.pair_class != PairClass::kFacingAway ? 1 : 0;
    }
  // Not vacuous: many pairs face each other and are dark only because the walls occlude.
  EXPECT_GT(needed_occlusion, static_cast<int>(box.inside.size()) / 2);
  EXPECT_GT(v->counters().segment_queries.load(), 1000u);
}

TEST(Leak, ARemovedTriangleLetsLightIn) {
  // Control: the same test fails when the box has a hole, so it can detect leaks.
  LeakBox box = make_leak_box(5);
  auto& hole = box.scene.patches[box.inside[3]].vertices;  // a triangle of the wall x = 0
  const Vec3 c = (hole[0] + hole[1] + hole[2]) / 3.0;
  hole = {{5, 5, 5}, {5.1, 5, 5}, {5, 5.1, 5}};  // moved away: the wall has a hole
  const auto v = make_visibility(box.scene);
  EXPECT_FALSE(v->segment_blocked({-0.5, c.y(), c.z()}, box.emitters[0], {0.3, c.y(), c.z()}, -1));
  double light = 0.0;
  for (int p : box.inside)
    light += v->estimate(box.scene.patches[box.emitters[0]].vertices, box.emitters[0], box.scene.patches[p].vertices, p,
                         256, 1)
                 .fraction;
  EXPECT_GT(light, 0.0);
}

}  // namespace
}  // namespace hrad
