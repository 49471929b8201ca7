// ElementHierarchy::balance() against the restricted quadtree's definition, checked by brute force
// on the leaves' geometry (every corner of every coplanar leaf against every leaf edge), independent
// of the half-edge mesh the balance and the output mesh read; and the output mesh of balanced leaves is
// crack-free: every output vertex lying inside another face's edge is a vertex of that face.
#include "hrad/mesh/element_hierarchy.h"

#include <gtest/gtest.h>

#include <vector>

#include "hrad/geometry/polygon.h"
#include "test_scene.h"

namespace hrad {
namespace {

using test::make_scene;

constexpr double kTol = 1e-9;

// Points strictly inside segment (a, b), farther than kTol from both ends.
bool inside(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double t = (p - a).dot(d) / d.squaredNorm();
  const double len = d.norm();
  return t * len > kTol && t * len < len - kTol && (a + t * d - p).norm() <= kTol;
}

// For every leaf edge, the distinct corners of the other leaves strictly inside it.
std::vector<std::vector<Vec3>> corners_inside_edges(const ElementHierarchy& h) {
  const std::vector<NodeId> leaves = h.all_leaves();
  std::vector<std::vector<Vec3>> out;
  for (const NodeId f : leaves) {
    const ElementNode& e = h.node(f);
    for (int k = 0; k < e.vertex_count; ++k) {
      const Vec3 &a = e.vertices[static_cast<std::size_t>(k)],
                 &b = e.vertices[static_cast<std::size_t>((k + 1) % e.vertex_count)];
      std::vector<Vec3> found;
      for (const NodeId g : leaves)
        for (const Vec3& p : h.node(g).polygon())
          if (inside(p, a, b) &&
              std::none_of(found.begin(), found.end(), [&](const Vec3& q) { return (q - p).norm() <= kTol; }))
            found.push_back(p);
      out.push_back(found);
    }
  }
  return out;
}

// The largest number of corners inside one leaf edge; each single one must be the edge's midpoint.
std::size_t worst_edge(const ElementHierarchy& h) {
  std::size_t worst = 0;
  for (const auto& c : corners_inside_edges(h)) worst = std::max(worst, c.size());
  return worst;
}

// Refines towards the point `x` of patch 0: the leaf containing it, `depth` times.
void refine_towards(ElementHierarchy& h, int patch, const Vec3& x, int depth) {
  NodeId id = h.root(patch);
  for (int d = 0; d < depth; ++d) {
    const NodeId first = h.split(id);
    id = first;
    double best = INFINITY;
    for (NodeId c = first; c < first + 4; ++c) {
      const double r = (polygon_centroid(h.node(c).polygon()) - x).norm();
      if (r < best) best = r, id = c;
    }
  }
}

TEST(Balance, ADeeplyRefinedQuadtreeGetsAtMostOneCornerPerEdgeAtItsMidpoint) {
  const Scene s = make_scene({{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}});
  ElementHierarchy h(s);
  // Towards a point beside the centre: the leaves hugging the centre are 5 levels finer than the
  // first level's leaves across the midlines.
  refine_towards(h, 0, Vec3(0.51, 0.51, 0), 6);
  ASSERT_GE(worst_edge(h), 3u);
  const std::size_t before = h.all_leaves().size();
  const std::size_t splits = h.balance();
  EXPECT_GT(splits, 0u);
  EXPECT_EQ(h.all_leaves().size(), before + 3 * splits);
  for (const NodeId f : h.all_leaves()) {
    const ElementNode& e = h.node(f);
    for (int k = 0; k < e.vertex_count; ++k) {
      const Vec3 &a = e.vertices[static_cast<std::size_t>(k)],
                 &b = e.vertices[static_cast<std::size_t>((k + 1) % e.vertex_count)];
      std::size_t n = 0;
      for (const NodeId g : h.all_leaves())
        for (const Vec3& p : h.node(g).polygon())
          if (inside(p, a, b)) {
            EXPECT_LT((p - 0.5 * (a + b)).norm(), kTol) << "a corner inside an edge away from its midpoint";
            ++n;
          }
      // The midpoint is a corner of both finer neighbours on that side: counted twice at most.
      EXPECT_LE(n, 2u);
    }
  }
  EXPECT_LE(worst_edge(h), 1u);
  // Balanced leaves stay balanced: a second pass splits nothing, and neither does a uniform mesh.
  EXPECT_EQ(h.balance(), 0u);
  ElementHierarchy uniform(s);
  uniform.subdivide_uniform(1.0 / 64.0);
  EXPECT_EQ(uniform.balance(), 0u);
}

TEST(Balance, CrossesCoplanarPatchesAtTJunctionsButNotCreases) {
  // A 2 x 2 floor patch beside two 1 x 1 patches (a T-junction at (2, 1)) and a wall standing on the
  // floor's far edge. Refining the small patch at its corner next to the floor must make the floor
  // split (coplanar, one material), the wall must not (a crease: its vertices are its own).
  const Scene s = make_scene({{{0, 0, 0}, {2, 0, 0}, {2, 0, -2}, {0, 0, -2}},
                              {{2, 0, 0}, {3, 0, 0}, {3, 0, -1}, {2, 0, -1}},
                              {{2, 0, -1}, {3, 0, -1}, {3, 0, -2}, {2, 0, -2}},
                              {{0, 0, 0}, {0, 2, 0}, {0, 2, -2}, {0, 0, -2}}});
  ElementHierarchy h(s);
  refine_towards(h, 1, Vec3(2.001, 0, -0.5), 5);
  refine_towards(h, 3, Vec3(0, 0.001, -1), 5);  // the wall is refined along the crease too
  ASSERT_GE(worst_edge(h), 3u);
  const std::size_t wall_leaves = h.leaves(3).size();
  EXPECT_GT(h.balance(), 0u);
  EXPECT_GT(h.leaves(0).size(), 1u);
  // Within each plane (the floor's three patches; the wall) no edge holds two corners.
  for (const NodeId f : h.all_leaves()) {
    const ElementNode& e = h.node(f);
    for (int k = 0; k < e.vertex_count; ++k) {
      const Vec3 &a = e.vertices[static_cast<std::size_t>(k)],
                 &b = e.vertices[static_cast<std::size_t>((k + 1) % e.vertex_count)];
      std::vector<Vec3> found;
      for (const NodeId g : h.all_leaves()) {
        if ((h.node(g).patch == 3) != (e.patch == 3)) continue;  // other plane
        for (const Vec3& p : h.node(g).polygon())
          if (inside(p, a, b) &&
              std::none_of(found.begin(), found.end(), [&](const Vec3& q) { return (q - p).norm() <= kTol; }))
            found.push_back(p);
      }
      EXPECT_LE(found.size(), 1u) << "patch " << e.patch;
    }
  }
  // Neither plane splits for the other: the wall balances as it would alone, and the floor (whose
  // leaves along the crease are coarse against the wall's) as it would without the wall.
  ElementHierarchy wall_alone(make_scene({s.patches[3].vertices}));
  refine_towards(wall_alone, 0, Vec3(0, 0.001, -1), 5);
  wall_alone.balance();
  EXPECT_EQ(h.leaves(3).size(), wall_alone.leaves(0).size());
  EXPECT_GT(h.leaves(3).size(), wall_leaves);
  ElementHierarchy floor_alone(make_scene({s.patches[0].vertices, s.patches[1].vertices, s.patches[2].vertices}));
  refine_towards(floor_alone, 1, Vec3(2.001, 0, -0.5), 5);
  floor_alone.balance();
  EXPECT_EQ(h.leaves(0).size(), floor_alone.leaves(0).size());
}

TEST(Balance, TheOutputMeshOfBalancedLeavesIsCrackFree) {
  // Every output vertex lying strictly inside an edge of another face of its plane is a vertex of
  // that face (a T-vertex the face interpolates), and each face edge holds at most one such vertex.
  const Scene s = make_scene({{{0, 0, 0}, {2, 0, 0}, {2, 0, -2}, {0, 0, -2}},
                              {{2, 0, 0}, {3, 0, 0}, {3, 0, -1}, {2, 0, -1}},
                              {{2, 0, -1}, {3, 0, -1}, {3, 0, -2}, {2, 0, -2}}});
  ElementHierarchy h(s);
  refine_towards(h, 1, Vec3(2.001, 0, -0.5), 5);
  h.balance();
  const Solution sol = h.to_solution();
  for (std::size_t f = 0; f < sol.faces.size(); ++f) {
    const std::vector<int>& face = sol.faces[f];
    // The face's own corners are its leaf's; any other vertex of it lies inside one of its edges.
    const ElementNode& e = h.node(h.all_leaves()[f]);
    for (int k = 0; k < e.vertex_count; ++k) {
      const Vec3 &a = e.vertices[static_cast<std::size_t>(k)],
                 &b = e.vertices[static_cast<std::size_t>((k + 1) % e.vertex_count)];
      std::size_t on_edge = 0;
      for (std::size_t v = 0; v < sol.vertices.size(); ++v) {
        if (!inside(sol.vertices[v], a, b)) continue;
        EXPECT_NE(std::find(face.begin(), face.end(), static_cast<int>(v)), face.end())
            << "vertex " << v << " inside an edge of face " << f << " but not one of its vertices";
        ++on_edge;
      }
      EXPECT_LE(on_edge, 1u) << "face " << f;
    }
  }
}

}  // namespace
}  // namespace hrad
