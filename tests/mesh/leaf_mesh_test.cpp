// The leaf mesh (ElementHierarchy's half-edge mesh, copied out by to_solution()) against the leaves'
// geometry alone: every output face is its leaf's polygon holding, in order from corner 0, exactly
// the output positions that lie on the leaf's boundary (a T-vertex on an edge is in the face: no
// crack), after random refinement of scenes with T-junctions between patches, creases, triangles
// beside quads, and the Cornell box.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <set>
#include <vector>

#include "hrad/io/scene_reader.h"
#include "hrad/mesh/element_hierarchy.h"
#include "support/source_tree.h"
#include "test_scene.h"

namespace hrad {
namespace {

using test::make_scene;

constexpr double kLeafTol = 1e-9;

// The distinct positions of `points` on the boundary of `polygon` (corners included), in order
// along the boundary from corner 0.
std::vector<Vec3> boundary_points(const std::vector<Vec3>& points, std::span<const Vec3> polygon) {
  std::vector<std::pair<double, Vec3>> found;
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& a = polygon[k];
    const Vec3 d = polygon[(k + 1) % n] - a;
    const double len = d.norm();
    for (const Vec3& p : points) {
      const double t = (p - a).dot(d) / (len * len);
      if (t * len < -kLeafTol || t * len >= len - kLeafTol || (a + t * d - p).norm() > kLeafTol) continue;
      if (std::none_of(found.begin(), found.end(), [&](const auto& q) { return (q.second - p).norm() <= kLeafTol; }))
        found.emplace_back(static_cast<double>(k) + std::max(t, 0.0), p);
    }
  }
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Vec3> out;
  for (const auto& f : found) out.push_back(f.second);
  return out;
}

void expect_faces_hold_their_boundary(const ElementHierarchy& h) {
  const Solution sol = h.to_solution();
  const std::vector<NodeId> leaves = h.all_leaves();
  ASSERT_EQ(sol.faces.size(), leaves.size());
  std::set<std::array<double, 3>> distinct;
  std::vector<Vec3> positions;
  for (const Vec3& v : sol.vertices)
    if (distinct.insert({v.x(), v.y(), v.z()}).second) positions.push_back(v);
  // Every corner of every leaf is an output position (none lost to a weld or a missed split).
  for (const NodeId id : leaves)
    for (const Vec3& c : h.node(id).polygon()) ASSERT_TRUE(distinct.count({c.x(), c.y(), c.z()})) << "leaf " << id;
  for (std::size_t f = 0; f < leaves.size(); ++f) {
    const std::vector<Vec3> expected = boundary_points(positions, h.node(leaves[f]).polygon());
    ASSERT_EQ(sol.faces[f].size(), expected.size()) << "face " << f << " of patch " << sol.face_patch[f];
    for (std::size_t j = 0; j < expected.size(); ++j)
      EXPECT_EQ(sol.vertices[static_cast<std::size_t>(sol.faces[f][j])], expected[j])
          << "face " << f << " vertex " << j;
  }
}

// Splits `count` leaves drawn at random (fixed seed), from all patches.
void refine_at_random(ElementHierarchy& h, int count, unsigned seed) {
  std::mt19937 rng(seed);
  for (int i = 0; i < count; ++i) {
    const std::vector<NodeId> leaves = h.all_leaves();
    h.split(leaves[std::uniform_int_distribution<std::size_t>(0, leaves.size() - 1)(rng)]);
  }
}

// A 2 x 2 floor beside two 1 x 1 squares (a T-junction at (2, 1)), a triangle beside the lower
// square, and a wall standing on the floor's edge y = 0 (a crease).
Scene junctions_scene() {
  return make_scene({{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}},
                     {{2, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2, 1, 0}},
                     {{2, 1, 0}, {3, 1, 0}, {3, 2, 0}, {2, 2, 0}},
                     {{3, 0, 0}, {4, 0, 0}, {3, 1, 0}},
                     {{0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0}}});
}

TEST(LeafMesh, NeighboursSplittingOneEdgeShareItsMidpoint) {
  // Two unit squares side by side, each split once: a 3 x 5 grid of vertices, not 16 (a midpoint
  // made twice) and no face missing the other side's midpoint.
  const Scene s =
      make_scene({{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}});
  ElementHierarchy h(s);
  h.split(0);
  EXPECT_EQ(h.to_solution().faces[4].size(), 5u);  // the unsplit square holds the midpoint (1, 0.5)
  h.split(1);
  const Solution sol = h.to_solution();
  EXPECT_EQ(sol.vertices.size(), 15u);
  for (const std::vector<int>& face : sol.faces) EXPECT_EQ(face.size(), 4u);
  expect_faces_hold_their_boundary(h);
}

TEST(LeafMesh, RandomRefinementAcrossJunctionsCreasesAndTrianglesIsCrackFree) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    ElementHierarchy h(junctions_scene());
    refine_at_random(h, 150, seed);
    expect_faces_hold_their_boundary(h);
    h.balance();
    expect_faces_hold_their_boundary(h);
  }
}

TEST(LeafMesh, LongPatchesCutIntoStripsAreCrackFree) {
  // A 32 x 1 strip of floor along a 32 x 32 square, a 1 x 20 wall standing on the strip's end and
  // facing it (a crease) and a 32 x 1.5 floor, long along v, beside the strip's other long edge:
  // strips put three points on each long edge at once, which the neighbours' loops must hold, and
  // the neighbours' own splits must find them again.
  const Scene s = make_scene({{{0, 0, 0}, {32, 0, 0}, {32, 1, 0}, {0, 1, 0}},
                              {{0, 1, 0}, {32, 1, 0}, {32, 33, 0}, {0, 33, 0}},
                              {{32, 0, 0}, {32, 0, 20}, {32, 1, 20}, {32, 1, 0}},
                              {{32, -1.5, 0}, {32, 0, 0}, {0, 0, 0}, {0, -1.5, 0}}});
  for (const unsigned seed : {7u, 8u}) {
    ElementHierarchy h(s);
    EXPECT_EQ(h.node(h.split(0)).vertices[1], Vec3(8, 0, 0));  // strips: u in [0, 1/4]
    EXPECT_EQ(h.to_solution().faces[4].size(), 7u);            // the square holds the 3 T-vertices
    refine_at_random(h, 120, seed);
    expect_faces_hold_their_boundary(h);
    h.balance();
    expect_faces_hold_their_boundary(h);
  }
}

TEST(LeafMesh, CopiesRefineApart) {
  ElementHierarchy h(junctions_scene());
  refine_at_random(h, 20, 4);
  ElementHierarchy copy = h;
  const Solution before = h.to_solution();
  refine_at_random(copy, 40, 5);
  const Solution after = h.to_solution();
  EXPECT_EQ(after.vertices, before.vertices);
  EXPECT_EQ(after.faces, before.faces);
  expect_faces_hold_their_boundary(copy);
  ElementHierarchy moved = std::move(copy);
  expect_faces_hold_their_boundary(moved);
}

TEST(LeafMesh, CornellBoxRefinedUnevenlyIsCrackFree) {
  const Scene s = read_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  ElementHierarchy h(s);
  refine_at_random(h, 300, 6);
  h.balance();
  expect_faces_hold_their_boundary(h);
}

TEST(LeafMesh, NonManifoldInputKeepsEveryLeafAndItsCorners) {
  // Two floor halves meeting along x = 1, a wall standing on that line (three faces on one edge), and
  // a copy of the first half lying on it: the faces that cannot join the half-edge mesh get their own
  // vertices and still split, balance and come out, each with its leaf's corners in order.
  const Scene s = make_scene({{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
                              {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}},
                              {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
                              {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}});
  ElementHierarchy h(s);
  refine_at_random(h, 120, 7);
  h.balance();
  const Solution sol = h.to_solution();
  const std::vector<NodeId> leaves = h.all_leaves();
  ASSERT_EQ(sol.faces.size(), leaves.size());
  for (std::size_t f = 0; f < leaves.size(); ++f) {
    const ElementNode& e = h.node(leaves[f]);
    std::size_t next = 0;  // the leaf's corners appear in the face in order, corner 0 first
    for (const int v : sol.faces[f])
      if (next < static_cast<std::size_t>(e.vertex_count) &&
          sol.vertices[static_cast<std::size_t>(v)] == e.vertices[next])
        ++next;
    EXPECT_EQ(next, static_cast<std::size_t>(e.vertex_count)) << "face " << f;
    EXPECT_EQ(sol.vertices[static_cast<std::size_t>(sol.faces[f][0])], e.vertices[0]) << "face " << f;
  }
  // The wall, outside the half-edge mesh of the floor, is a conforming mesh of its own: each of its
  // faces holds the wall's positions on its leaf's boundary (its T-vertices).
  std::vector<Vec3> wall;
  for (std::size_t f = 0; f < leaves.size(); ++f)
    if (sol.face_patch[f] == 2)
      for (const int v : sol.faces[f]) wall.push_back(sol.vertices[static_cast<std::size_t>(v)]);
  std::size_t t_vertices = 0;
  for (std::size_t f = 0; f < leaves.size(); ++f) {
    if (sol.face_patch[f] != 2) continue;
    const std::vector<Vec3> expected = boundary_points(wall, h.node(leaves[f]).polygon());
    ASSERT_EQ(sol.faces[f].size(), expected.size()) << "wall face " << f;
    t_vertices += expected.size() - static_cast<std::size_t>(h.node(leaves[f]).vertex_count);
  }
  EXPECT_GT(t_vertices, 0u);  // the wall's refinement is uneven: the check saw T-vertices
}

}  // namespace
}  // namespace hrad
