// Segment occlusion: the touching rules of cgal_visibility.cpp, exactness on shared edges, and
// agreement with an independent floating-point ray/triangle test away from degeneracies.
#include <gtest/gtest.h>

#include <random>

#include "hrad/visibility/visibility.h"
#include "test_scenes.h"

namespace hrad {
namespace {

using test::add_patch;
using test::empty_scene;
using test::square_z;

TEST(SegmentBlocked, InteriorHitAndMiss) {
  Scene s = empty_scene();
  const int occ = add_patch(s, square_z(0, 1, 0, 1, 0, true));
  const int low = add_patch(s, square_z(-5, 5, -5, 5, -1, true));
  const int high = add_patch(s, square_z(-5, 5, -5, 5, 1, false));
  const auto v = make_visibility(s);
  EXPECT_TRUE(v->segment_blocked({0.5, 0.5, -1}, low, {0.3, 0.6, 1}, high));
  EXPECT_FALSE(v->segment_blocked({1.5, 0.5, -1}, low, {1.5, 0.6, 1}, high));
  // The occluder's own patch never blocks when it is an endpoint's patch.
  EXPECT_FALSE(v->segment_blocked({0.5, 0.5, 0}, occ, {0.3, 0.6, 1}, high));
  EXPECT_FALSE(v->segment_blocked({0.5, 0.5, -1}, low, {0.3, 0.6, 1}, occ));
  // Degenerate segment: the open segment is empty.
  EXPECT_FALSE(v->segment_blocked({0.5, 0.5, 0}, -1, {0.5, 0.5, 0}, -1));
  EXPECT_EQ(v->counters().segment_queries.load(), 5u);
}

TEST(SegmentBlocked, SharedEdgesAndVerticesOfAnOccludingMeshBlock) {
  // A square split into four triangles around its centre (0.5, 0.5, 0), each its own patch.
  Scene s = empty_scene();
  const Vec3 c{0.5, 0.5, 0}, p00{0, 0, 0}, p10{1, 0, 0}, p11{1, 1, 0}, p01{0, 1, 0};
  add_patch(s, {p00, p10, c});
  add_patch(s, {p10, p11, c});
  add_patch(s, {p11, p01, c});
  add_patch(s, {p01, p00, c});
  const auto v = make_visibility(s);
  // Through the shared vertex, perpendicular and oblique.
  EXPECT_TRUE(v->segment_blocked({0.5, 0.5, -1}, -1, {0.5, 0.5, 1}, -1));
  EXPECT_TRUE(v->segment_blocked({0.25, 0.75, -1}, -1, {0.75, 0.25, 1}, -1));
  // Through the middle of a shared (diagonal) edge, and through an outer corner.
  EXPECT_TRUE(v->segment_blocked({0.25, 0.25, -1}, -1, {0.25, 0.25, 1}, -1));
  EXPECT_TRUE(v->segment_blocked({0.0, 0.0, -1}, -1, {0.0, 0.0, 1}, -1));
  EXPECT_TRUE(v->segment_blocked({-1, -1, -1}, -1, {1, 1, 1}, -1));
  // Just outside the outer corner.
  EXPECT_FALSE(v->segment_blocked({-1, -1, -1}, -1, {1, 0.999999999, 1}, -1));
  EXPECT_FALSE(v->segment_blocked({-1.000000001, -1, -1}, -1, {1, 1, 1}, -1));
}

TEST(SegmentBlocked, CrossingsExactlyOnASharedEdgeAlwaysBlock) {
  // Two triangles share the edge (0,0,0)-(4,12,0) on the line y = 3x. A segment from
  // (ax, 3ax, 1) to (bx, 3bx, -1) crosses z = 0 at its midpoint, which lies exactly on that
  // line; floating-point ray tests miss some of these (the light leaks through the crack).
  Scene s = empty_scene();
  add_patch(s, {{0, 0, 0}, {4, 0, 0}, {4, 12, 0}});
  add_patch(s, {{0, 0, 0}, {4, 12, 0}, {0, 12, 0}});
  const auto v = make_visibility(s);
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> coord(1, 4 * 1024 - 1);
  int tested = 0;
  for (int i = 0; i < 20000; ++i) {
    const double ax = coord(rng) / 1024.0, bx = coord(rng) / 1024.0;  // 3 ax is exact
    const double mid = 0.5 * (ax + bx);
    if (mid <= 0.0 || mid >= 4.0) continue;
    ++tested;
    ASSERT_TRUE(v->segment_blocked({ax, 3 * ax, 1}, -1, {bx, 3 * bx, -1}, -1)) << ax << " " << bx;
  }
  EXPECT_GT(tested, 19000);
}

TEST(SegmentBlocked, EndpointsTouchingOtherPatchesDoNotBlock) {
  Scene s = empty_scene();
  const int floor = add_patch(s, square_z(0, 1, 0, 1, 0, true));
  // A wall x = 1 (front facing -x) sharing the floor's edge, and a ceiling.
  const int wall = add_patch(s, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}});
  const int ceiling = add_patch(s, square_z(0, 1, 0, 1, 1, false));
  // A light coplanar with the ceiling and overlapping it (the published Cornell box).
  const int light = add_patch(s, square_z(0.4, 0.6, 0.4, 0.6, 1, false));
  const auto v = make_visibility(s);
  // From a point on the floor/wall edge into the room: the wall touches only the endpoint.
  EXPECT_FALSE(v->segment_blocked({1, 0.5, 0}, floor, {0.2, 0.5, 1}, ceiling));
  // From the light, inside the ceiling's polygon, down to the floor and to the wall.
  EXPECT_FALSE(v->segment_blocked({0.5, 0.5, 1}, light, {0.1, 0.9, 0}, floor));
  EXPECT_FALSE(v->segment_blocked({0.5, 0.5, 1}, light, {1, 0.2, 0.3}, wall));
  // Upwards from the light the ceiling touches it only at the endpoint too (open segment).
  EXPECT_FALSE(v->segment_blocked({0.5, 0.5, 1}, light, {0.5, 0.5, 2}, -1));
  // But a segment from below the floor to the ceiling crosses the floor: blocked.
  EXPECT_TRUE(v->segment_blocked({0.5, 0.5, -1}, -1, {0.5, 0.5, 1}, ceiling));
}

TEST(SegmentBlocked, GrazingRulesInTheOccludersPlane) {
  Scene s = empty_scene();
  add_patch(s, square_z(0, 1, 0, 1, 0, true));  // the occluder, in z = 0
  const auto v = make_visibility(s);
  // In the plane, crossing the square: runs along the surface, blocked.
  EXPECT_TRUE(v->segment_blocked({-1, 0.5, 0}, -1, {2, 0.5, 0}, -1));
  // In the plane, along an edge line: blocked (edges are closed).
  EXPECT_TRUE(v->segment_blocked({-1, 0, 0}, -1, {2, 0, 0}, -1));
  // In the plane, through a corner only: blocked.
  EXPECT_TRUE(v->segment_blocked({-1, 1, 0}, -1, {1, -1, 0}, -1));
  // In the plane, passing beside: free.
  EXPECT_FALSE(v->segment_blocked({-1, 1.5, 0}, -1, {2, 1.25, 0}, -1));
  // In the plane, ending on the edge from outside: touches at the endpoint only.
  EXPECT_FALSE(v->segment_blocked({-1, 0.5, 0}, -1, {0, 0.5, 0}, -1));
  // Starting on the edge and going in: blocked; starting on the edge and going out: free.
  EXPECT_TRUE(v->segment_blocked({0, 0.5, 0}, -1, {0.5, 0.5, 0}, -1));
  EXPECT_FALSE(v->segment_blocked({0, 0.5, 0}, -1, {-0.5, 0.7, 0}, -1));
  // Starting at a corner: into the corner's cone blocked, along an edge blocked, outside free.
  EXPECT_TRUE(v->segment_blocked({0, 0, 0}, -1, {0.3, 0.2, 0}, -1));
  EXPECT_TRUE(v->segment_blocked({0, 0, 0}, -1, {0.3, 0, 0}, -1));
  EXPECT_FALSE(v->segment_blocked({0, 0, 0}, -1, {-0.3, 0, 0}, -1));
  EXPECT_FALSE(v->segment_blocked({0, 0, 0}, -1, {0.3, -0.1, 0}, -1));
  // Both endpoints inside the square: blocked.
  EXPECT_TRUE(v->segment_blocked({0.2, 0.2, 0}, -1, {0.7, 0.4, 0}, -1));
  // Just above the plane (grazing but not in it): free.
  EXPECT_FALSE(v->segment_blocked({-1, 0.5, 1e-300}, -1, {2, 0.5, 1e-300}, -1));
}

TEST(SegmentBlocked, OccludersTouchingTheEndpointsPolygonsStillBlockTheirInterior) {
  // A block standing on the floor (no bottom face): its side faces touch the floor.
  Scene s = empty_scene();
  const int floor = add_patch(s, square_z(-2, 2, -2, 2, 0, true));
  const int top = add_patch(s, square_z(0, 1, 0, 1, 1, true));
  add_patch(s, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}});  // side y = 0, front -y
  const int ceiling = add_patch(s, square_z(-2, 2, -2, 2, 3, false));
  const auto v = make_visibility(s);
  // From the floor under the block to the ceiling: the top blocks.
  EXPECT_TRUE(v->segment_blocked({0.5, 0.5, 0}, floor, {0.5, 0.5, 3}, ceiling));
  // From the floor in front of the block, passing the side face: blocked by it.
  EXPECT_TRUE(v->segment_blocked({0.5, -0.5, 0}, floor, {0.5, 0.5, 1.5}, -1));
  // From the foot of the side face (on its bottom edge) away from the block: free.
  EXPECT_FALSE(v->segment_blocked({0.5, 0, 0}, floor, {0.5, -1, 3}, ceiling));
  // From the foot of the side face up along it: grazes the side face, blocked by the rule.
  EXPECT_TRUE(v->segment_blocked({0.5, 0, 0}, floor, {0.5, 0, 3}, ceiling));
  // From the top's own surface upwards: own patch, free.
  EXPECT_FALSE(v->segment_blocked({0.5, 0.5, 1}, top, {0.5, 0.5, 3}, ceiling));
}

// Independent reference: Moller & Trumbore (1997) in doubles, trusted only when the crossing is
// far from the triangle's edges and the segment's ends.
int reference_hit(const Vec3& a, const Vec3& b, const Vec3& p0, const Vec3& p1, const Vec3& p2, double margin) {
  const Vec3 d = b - a, e1 = p1 - p0, e2 = p2 - p0;
  const Vec3 h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-9) return -1;
  const Vec3 s = a - p0;
  const double u = s.dot(h) / det;
  const Vec3 q = s.cross(e1);
  const double w = d.dot(q) / det, t = e2.dot(q) / det;
  const double m = std::min({u, w, 1 - u - w, t, 1 - t});
  if (std::abs(m) < margin || std::abs(u) < margin || std::abs(w) < margin || std::abs(1 - u - w) < margin) return -1;
  return (u >= 0 && w >= 0 && u + w <= 1 && t > 0 && t < 1) ? 1 : 0;
}

TEST(SegmentBlocked, AgreesWithFloatingPointReferenceAwayFromDegeneracies) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rv = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  Scene s = empty_scene();
  std::vector<std::array<Vec3, 3>> tris;
  for (int i = 0; i < 40; ++i) {
    const Vec3 c = rv();
    const std::array<Vec3, 3> t{c + 0.3 * rv(), c + 0.3 * rv(), c + 0.3 * rv()};
    if ((t[1] - t[0]).cross(t[2] - t[0]).norm() < 1e-3) continue;
    tris.push_back(t);
    add_patch(s, {t[0], t[1], t[2]});
  }
  const auto v = make_visibility(s);
  int compared = 0, blocked = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3 a = 1.5 * rv(), b = 1.5 * rv();
    int expected = 0;
    bool trusted = true;
    for (const auto& t : tris) {
      const int r = reference_hit(a, b, t[0], t[1], t[2], 1e-6);
      if (r < 0) {
        trusted = false;
        break;
      }
      expected |= r;
    }
    if (!trusted) continue;
    ++compared;
    blocked += expected;
    ASSERT_EQ(v->segment_blocked(a, -1, b, -1), expected == 1) << i;
  }
  EXPECT_GT(compared, 4000);
  EXPECT_GT(blocked, 500);
  EXPECT_LT(blocked, compared - 500);
}

}  // namespace
}  // namespace hrad

namespace hrad {
namespace {

// The compact hierarchy and CGAL's AABB_tree only cull; both must give the same answers, also in
// degenerate configurations (integer grids: segments through shared edges, vertices, in planes).
TEST(SegmentBlocked, CompactHierarchyAndCgalTreeAgree) {
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> g(0, 8);
  auto gv = [&] { return Vec3(g(rng), g(rng), g(rng)); };
  for (int scene_id = 0; scene_id < 6; ++scene_id) {
    Scene s = test::empty_scene();
    while (s.patches.size() < 40) {
      const Vec3 a = gv(), b = gv(), c = gv();
      if ((b - a).cross(c - a).norm() == 0) continue;
      test::add_patch(s, {a, b, c});
    }
    const auto compact = make_visibility(s);
    VisibilityOptions o;
    o.cgal_tree_for_segments = true;
    const auto cgal = make_visibility(s, o);
    int blocked = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3 a = gv(), b = gv();
      const int pa = i % 3 == 0 ? -1 : int(rng() % s.patches.size()),
                pb = i % 5 == 0 ? -1 : int(rng() % s.patches.size());
      const bool x = compact->segment_blocked(a, pa, b, pb);
      ASSERT_EQ(x, cgal->segment_blocked(a, pa, b, pb)) << scene_id << " " << i;
      blocked += x;
    }
    EXPECT_GT(blocked, 400);
    EXPECT_LT(blocked, 3900);
  }
}

}  // namespace
}  // namespace hrad
