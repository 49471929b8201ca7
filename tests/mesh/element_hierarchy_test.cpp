#include "hrad/mesh/element_hierarchy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "hrad/formfactor/simpson_rule.h"
#include "hrad/geometry/polygon.h"
#include "test_scene.h"

namespace hrad {
namespace {

using test::make_scene;

std::vector<Vec3> quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) { return {a, b, c, d}; }

double leaf_area_sum(const ElementHierarchy& h, int patch) {
  double sum = 0.0;
  for (NodeId id : h.leaves(patch)) sum += h.node(id).area;
  return sum;
}

// Two overlapping slivers in one plane that meet at a welded corner, and a quad in another plane with
// two corners 2e-5 apart (pieces of a wall cut around furniture, as a modeller's boolean leaves them):
// OpenMesh's add_face() would re-link around the shared corner and assert on a half-edge without a
// successor. The mesh takes each such face with vertices of its own instead, and splits as usual.
TEST(ElementHierarchy, SliversAtAWeldedCornerBuildAndSplit) {
  Scene s = make_scene({{{-479.99980000000005, -800.00199999999995, -632.48327024793389},
                         {-444.00428415577198, -800.00199999999995, -599.99789999999996},
                         {-84.000000000000114, -800.00199999999995, -999.99900000000002}},
                        {{352.14474474022308, -800.00199999999995, -609.60496181975634},
                         {-84.000000016147055, -800.00199999999995, -999.9989999820591},
                         {-389.99833390461754, -800.00199999999995, -660.0008961903859}},
                        quad({420, -533.33280000000002, -684.99900000000002},
                             {113.99990000000001, -533.33280000000002, -345.00200000000001},
                             {-83.999989942896377, -533.33280000000002, -999.99896673042406},
                             {-83.999974400085478, -533.33280000000002, -999.9989840000535})});
  ElementHierarchy h(s);
  for (int p = 0; p < 3; ++p) {
    h.split(h.root(p));
    EXPECT_NEAR(leaf_area_sum(h, p), s.patches[static_cast<std::size_t>(p)].area,
                1e-12 * s.patches[static_cast<std::size_t>(p)].area);
  }
}

TEST(ElementHierarchy, UniformSubdivisionAreasSumToPatchArea) {
  // An irregular convex quad and a scalene triangle: the 1-to-4 splits must still tile them.
  const Scene s =
      make_scene({quad({0, 0, 0}, {3, 0.2, 0}, {2.5, 2, 0}, {-0.3, 1.4, 0}), {{0, 0, 1}, {2, 0.5, 1.5}, {0.7, 3, 1}}});
  ElementHierarchy h(s);
  const double max_area = s.patches[0].area / 50.0;
  h.subdivide_uniform(max_area);
  for (int p = 0; p < 2; ++p) {
    EXPECT_NEAR(leaf_area_sum(h, p), s.patches[p].area, 1e-12 * s.patches[p].area) << "patch " << p;
    for (NodeId id : h.leaves(p)) {
      EXPECT_LE(h.node(id).area, max_area);
      // the parent was too large, or it is the root
      if (h.node(id).parent != kNoNode) EXPECT_GT(h.node(h.node(id).parent).area, max_area);
      EXPECT_NEAR(h.node(id).area, polygon_area(h.node(id).polygon()), 1e-12);
      // children keep the patch's orientation
      EXPECT_GT(newell_normal(h.node(id).polygon()).dot(s.patches[p].normal), 0.0);
    }
  }
  // A triangle's four children have equal areas (midpoint subdivision): 4^depth leaves of area A/4^depth.
  const std::vector<NodeId> tri = h.leaves(1);
  const int depth = h.node(tri[0]).depth;
  EXPECT_EQ(tri.size(), static_cast<std::size_t>(1) << (2 * depth));
  for (NodeId id : tri) EXPECT_NEAR(h.node(id).area, s.patches[1].area / double(tri.size()), 1e-12);
}

// Half the ratio of a quad's two mid-line lengths, max over both orders: its aspect.
double aspect(const ElementNode& n) {
  const auto& v = n.vertices;
  const double u = ((v[1] + v[2]) - (v[3] + v[0])).norm(), w = ((v[2] + v[3]) - (v[0] + v[1])).norm();
  return std::max(u / w, w / u);
}

Vec3 bilinear(const ElementNode& n, double u, double v) {
  const auto& p = n.vertices;
  return (1 - u) * (1 - v) * p[0] + u * (1 - v) * p[1] + u * v * p[2] + (1 - u) * v * p[3];
}

TEST(ElementHierarchy, LongQuadsSplitAcrossTheirLengthAndElementsStayWithinTheStripAspect) {
  // Two irregular quads about 60 : 1, long along u and along v, and two rectangles either side of
  // the threshold.
  const Scene s = make_scene(
      {quad({0, 0, 0}, {60, 0, 0}, {59, 1.5, 0}, {1, 0.5, 0}), quad({0, 0, 1}, {1.2, 0, 1}, {1.5, 61, 1}, {0, 60, 1}),
       quad({0, 0, 2}, {16, 0, 2}, {16, 1, 2}, {0, 1, 2}), quad({0, 0, 3}, {16.5, 0, 3}, {16.5, 1, 3}, {0, 1, 3})});
  ElementHierarchy h(s);
  EXPECT_EQ(split_kind_of(h.node(0)), SplitKind::kStripsU);
  EXPECT_EQ(split_kind_of(h.node(1)), SplitKind::kStripsV);
  EXPECT_EQ(split_kind_of(h.node(2)), SplitKind::kQuadrants);  // 16 : 1 keeps its shape
  EXPECT_EQ(split_kind_of(h.node(3)), SplitKind::kStripsU);
  for (int p = 0; p < 4; ++p) h.subdivide_uniform(h.root(p), s.patches[static_cast<std::size_t>(p)].area / 1000.0);
  for (int p = 0; p < 4; ++p) {
    EXPECT_NEAR(leaf_area_sum(h, p), s.patches[static_cast<std::size_t>(p)].area, 1e-12 * s.patches[p].area);
    for (NodeId id : h.leaves(p)) {
      EXPECT_LT(aspect(h.node(id)), kStripAspect * 1.05) << "patch " << p << " leaf " << id;
      EXPECT_GT(newell_normal(h.node(id).polygon()).dot(s.patches[static_cast<std::size_t>(p)].normal), 0.0);
    }
  }
  // Each child is the parent's bilinear map on quad_child_uv() (what push_pull's restriction assumes).
  std::set<SplitKind> kinds;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const ElementNode& n = h.node(static_cast<NodeId>(i));
    if (n.is_leaf()) continue;
    kinds.insert(n.split);
    for (int k = 0; k < 4; ++k) {
      const std::array<std::array<double, 2>, 4> uv = quad_child_uv(n.split, k);
      for (int m = 0; m < 4; ++m)
        EXPECT_LT((h.node(n.first_child + k).vertices[m] - bilinear(n, uv[m][0], uv[m][1])).norm(), 1e-12)
            << "node " << i << " child " << k << " corner " << m;
    }
  }
  EXPECT_EQ(kinds.size(), 3u);
}

TEST(ElementHierarchy, SplitIsIdempotentAndInheritsMaterial) {
  Scene s = make_scene({quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0})});
  s.materials[0].emission = Rgb(1, 2, 3);
  ElementHierarchy h(s);
  const NodeId first = h.split(0);
  EXPECT_EQ(h.split(0), first);
  EXPECT_EQ(h.size(), 5u);
  for (int k = 0; k < 4; ++k) {
    const ElementNode& c = h.node(first + k);
    EXPECT_EQ(c.parent, 0);
    EXPECT_EQ(c.depth, 1);
    EXPECT_DOUBLE_EQ(c.area, 0.25);
    EXPECT_TRUE((c.emission == Rgb(1, 2, 3)).all());
    EXPECT_TRUE((c.reflectance == Rgb::Constant(0.5)).all());
  }
}

TEST(ElementHierarchy, PullAveragesByArea) {
  const Scene s = make_scene({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}});
  ElementHierarchy h(s);
  const NodeId first = h.split(0);
  const NodeId grand = h.split(first + 3);
  for (NodeId id : h.leaves(0)) h.node(id).radiosity = Rgb::Constant(0.0);
  h.node(grand).radiosity = Rgb::Constant(16.0);  // 1/16 of the area
  h.pull_radiosity();
  EXPECT_DOUBLE_EQ(h.node(first + 3).radiosity[0], 4.0);
  EXPECT_DOUBLE_EQ(h.node(0).radiosity[0], 1.0);
}

// --- the leaf mesh --------------------------------------------------------------------------

// Independent conformity check: no output vertex lies strictly inside an output edge, and no
// edge is used by more than two faces (in one direction at most once).
void expect_conforming(const Solution& sol, double tol) {
  std::map<std::pair<int, int>, int> directed;
  std::map<std::pair<int, int>, int> undirected;
  for (const auto& f : sol.faces) {
    for (std::size_t k = 0; k < f.size(); ++k) {
      const int a = f[k], b = f[(k + 1) % f.size()];
      ++directed[{a, b}];
      ++undirected[{std::min(a, b), std::max(a, b)}];
      const Vec3& pa = sol.vertices[static_cast<std::size_t>(a)];
      const Vec3& pb = sol.vertices[static_cast<std::size_t>(b)];
      const Vec3 d = pb - pa;
      for (const Vec3& p : sol.vertices) {
        const double t = (p - pa).dot(d) / d.squaredNorm();
        if (t * d.norm() <= tol || (1 - t) * d.norm() <= tol) continue;
        EXPECT_GT((pa + t * d - p).norm(), tol) << "a vertex lies inside edge " << a << "-" << b << " (crack)";
      }
    }
  }
  for (const auto& [e, n] : directed) EXPECT_EQ(n, 1) << "edge " << e.first << "-" << e.second;
  for (const auto& [e, n] : undirected) EXPECT_LE(n, 2) << "edge " << e.first << "-" << e.second;
}

// A big square beside two small squares (a T-junction across patches), all in z = 0.
Scene t_junction_scene() {
  return make_scene({quad({0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}), quad({2, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2, 1, 0}),
                     quad({2, 1, 0}, {3, 1, 0}, {3, 2, 0}, {2, 2, 0})});
}

TEST(LeafMesh, ConformingAcrossPatchesAndLevels) {
  const Scene s = t_junction_scene();
  ElementHierarchy h(s);
  // Refine unevenly: the small squares twice, one corner of the big square three times.
  h.subdivide_uniform(1, 1.0 / 16.0);
  h.subdivide_uniform(2, 1.0 / 16.0);
  NodeId id = 0;
  for (int level = 0; level < 3; ++level) id = h.split(id) + 1;  // toward corner (2, 0)
  const Solution sol = h.to_solution();
  ASSERT_EQ(sol.faces.size(), h.all_leaves().size());
  expect_conforming(sol, 1e-9);
  // The big square's leaf along x = 2 between y = 1 and 2 must have picked up the small leaves'
  // vertices at y = 1.25, 1.5, 1.75 (and the patch corner at y = 1).
  bool found = false;
  for (std::size_t f = 0; f < sol.faces.size(); ++f) {
    if (sol.face_patch[f] != 0) continue;
    int on_edge = 0;
    for (int v : sol.faces[f]) {
      const Vec3& p = sol.vertices[static_cast<std::size_t>(v)];
      if (std::abs(p.x() - 2) < 1e-12 && p.y() > 1 - 1e-12) ++on_edge;
    }
    if (on_edge == 5) found = true;
  }
  EXPECT_TRUE(found);
  // Coplanar patches share vertices: every distinct position appears once.
  std::set<std::array<double, 3>> positions;
  for (const Vec3& v : sol.vertices) positions.insert({v.x(), v.y(), v.z()});
  EXPECT_EQ(positions.size(), sol.vertices.size());
}

TEST(LeafMesh, ConstantFieldGivesConstantVertexRadiosity) {
  const Scene s = t_junction_scene();
  ElementHierarchy h(s);
  h.subdivide_uniform(1, 0.1);
  h.split(h.split(0) + 2);
  for (NodeId id : h.all_leaves()) h.node(id).radiosity = Rgb(0.3, 1.7, 5.0);
  const Solution sol = h.to_solution();
  ASSERT_EQ(sol.vertex_radiosity.size(), sol.vertices.size());
  for (const Rgb& b : sol.vertex_radiosity) EXPECT_NEAR((b - Rgb(0.3, 1.7, 5.0)).abs().maxCoeff(), 0.0, 1e-14);
  for (const Rgb& b : sol.patch_radiosity) EXPECT_NEAR((b - Rgb(0.3, 1.7, 5.0)).abs().maxCoeff(), 0.0, 1e-14);
}

TEST(LeafMesh, VertexRadiosityIsAreaWeightedAndPatchMeanIsAreaMean) {
  const Scene s = t_junction_scene();
  ElementHierarchy h(s);
  h.node(0).radiosity = Rgb::Constant(1.0);  // area 4
  h.node(1).radiosity = Rgb::Constant(2.0);  // area 1
  h.node(2).radiosity = Rgb::Constant(4.0);  // area 1
  const Solution sol = h.to_solution();
  // Vertex (2, 1) touches all three faces (it is a T-vertex inserted into the big square).
  for (std::size_t v = 0; v < sol.vertices.size(); ++v) {
    if ((sol.vertices[v] - Vec3(2, 1, 0)).norm() < 1e-12)
      EXPECT_NEAR(sol.vertex_radiosity[v][0], (4 + 2 + 4) / 6.0, 1e-14);
    if ((sol.vertices[v] - Vec3(0, 0, 0)).norm() < 1e-12) EXPECT_NEAR(sol.vertex_radiosity[v][0], 1.0, 1e-14);
  }
  EXPECT_EQ(sol.faces[0].size(), 5u);  // the big square gained the T-vertex (2, 1)
  h.split(1);
  h.node(h.node(1).first_child).radiosity = Rgb::Constant(6.0);
  const Solution sol2 = h.to_solution();
  EXPECT_NEAR(sol2.patch_radiosity[1][0], (6.0 + 3 * 2.0) / 4.0, 1e-14);
}

TEST(LeafMesh, CreasesKeepSeparateVerticesAndStayConforming) {
  // An L: floor (z up) and wall (facing +y... into the room) meeting along the x axis, refined
  // differently, so the crease has T-vertices on both sides.
  const Scene s =
      make_scene({quad({0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}), quad({0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0})});
  ElementHierarchy h(s);
  h.subdivide_uniform(0, 1.0);
  h.subdivide_uniform(1, 0.25);
  h.node(0).radiosity = Rgb::Constant(1.0);
  for (NodeId id : h.leaves(0)) h.node(id).radiosity = Rgb::Constant(1.0);
  for (NodeId id : h.leaves(1)) h.node(id).radiosity = Rgb::Constant(3.0);
  const Solution sol = h.to_solution();
  expect_conforming(sol, 1e-9);
  // No bleeding around the corner: each side's vertices carry its own constant.
  for (std::size_t f = 0; f < sol.faces.size(); ++f)
    for (int v : sol.faces[f])
      EXPECT_DOUBLE_EQ(sol.vertex_radiosity[static_cast<std::size_t>(v)][0], sol.face_patch[f] == 0 ? 1.0 : 3.0);
}

TEST(ElementHierarchy, ChildCornersAreTheParentsSimpsonPoints) {
  // The oracle reuses a parent's corner, edge-midpoint and centre points as its children's corners
  // (formfactor/simpson_rule.h child_corner_points()): bit-identical under split().
  Scene s;
  s.materials = {{"m", Rgb::Constant(0.5), Rgb::Zero()}};
  for (const std::vector<Vec3>& poly : {std::vector<Vec3>{{0, 0, 0}, {3, 0, 0}, {2, 1, 0}, {0.5, 1, 0}},
                                        std::vector<Vec3>{{0, 0, 0}, {2, 0.5, 0}, {0.3, 1.2, 0}}}) {
    Patch p;
    p.vertices = poly;
    p.normal = newell_normal(poly).normalized();
    p.area = polygon_area(poly);
    p.material = 0;
    s.patches = {p};
    ElementHierarchy h(s);
    const NodeId first = h.split(h.root(0));
    const SimpsonPoints parent = simpson_points(h.node(h.root(0)).polygon());
    for (int k = 0; k < 4; ++k) {
      const std::array<int, 4> corners = child_corner_points(static_cast<int>(poly.size()), k);
      const ElementNode& child = h.node(first + k);
      for (int c = 0; c < child.vertex_count; ++c) EXPECT_EQ(child.vertices[c], parent.x[corners[c]]) << k << " " << c;
    }
  }
}

}  // namespace
}  // namespace hrad
