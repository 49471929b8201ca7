#include "hrad/gather/leaf_quadtree.h"

#include <algorithm>
#include <cmath>

#include "hrad/geometry/polygon.h"
#include "hrad/mesh/element_hierarchy.h"

namespace hrad::detail {
namespace {

struct Builder {
  const Solution& solution;
  ElementHierarchy& regions;
  std::vector<LeafQuadtreeNode>& nodes;
  std::vector<Vec3>& vertices;
  std::vector<int>& children;
  std::vector<std::vector<Vec3>> leaf_polygons;
  std::vector<double> leaf_area;
  Vec3 normal;
  double tolerance = 0.0;  // distance, for containment
  std::size_t unplaced = 0;

  bool contains(std::span<const Vec3> region, const std::vector<Vec3>& leaf) const {
    for (std::size_t k = 0; k < region.size(); ++k) {
      const Vec3& a = region[k];
      const Vec3 edge = region[(k + 1) % region.size()] - a;
      const double slack = -tolerance * edge.norm();
      for (const Vec3& v : leaf)
        if (edge.cross(v - a).dot(normal) < slack) return false;
    }
    return true;
  }

  int add_node(std::span<const Vec3> polygon, LeafQuadtreeNode n) {
    n.first_vertex = static_cast<std::uint32_t>(vertices.size());
    n.vertex_count = static_cast<std::uint32_t>(polygon.size());
    vertices.insert(vertices.end(), polygon.begin(), polygon.end());
    nodes.push_back(n);
    return static_cast<int>(nodes.size() - 1);
  }

  // A leaf node; `region`, when given, is a region the leaf lies in. When the leaf fills it, the
  // region's 3 or 4 corners stand for the leaf's polygon, which may hold T-vertices on its edges
  // (the same point set, so the same factor; a quad's factor is the kernel's fastest case).
  int leaf_node(int face, NodeId region = kNoNode) {
    LeafQuadtreeNode n;
    n.leaf = face;
    n.area = leaf_area[static_cast<std::size_t>(face)];
    n.mean = solution.face_radiosity[static_cast<std::size_t>(face)];
    const std::vector<Vec3>& polygon = leaf_polygons[static_cast<std::size_t>(face)];
    if (region != kNoNode && polygon.size() > static_cast<std::size_t>(regions.node(region).vertex_count) &&
        std::abs(n.area - regions.node(region).area) <= 1e-9 * n.area)
      return add_node(regions.node(region).polygon(), n);
    return add_node(polygon, n);
  }

  // The node for the region `region` holding `leaves` (all contained in it).
  int build(NodeId region, const std::vector<int>& leaves) {
    if (leaves.size() == 1) return leaf_node(leaves.front(), region);
    std::vector<int> child_ids;
    if (regions.node(region).depth >= kLeafQuadtreeMaxDepth) {
      for (int f : leaves) child_ids.push_back(leaf_node(f));
      unplaced += leaves.size();
    } else {
      const NodeId first = regions.split(region);
      std::array<std::vector<int>, 4> placed;
      std::vector<int> rest;
      for (int f : leaves) {
        int k = 0;
        while (k < 4 && !contains(regions.node(first + k).polygon(), leaf_polygons[static_cast<std::size_t>(f)])) ++k;
        (k < 4 ? placed[static_cast<std::size_t>(k)] : rest).push_back(f);
      }
      for (int k = 0; k < 4; ++k)
        if (!placed[static_cast<std::size_t>(k)].empty())
          child_ids.push_back(build(first + k, placed[static_cast<std::size_t>(k)]));
      for (int f : rest) child_ids.push_back(leaf_node(f));
      unplaced += rest.size();
    }
    LeafQuadtreeNode n;
    n.first_child = static_cast<std::uint32_t>(children.size());
    n.child_count = static_cast<std::uint32_t>(child_ids.size());
    children.insert(children.end(), child_ids.begin(), child_ids.end());
    const std::span<const Vec3> polygon = regions.node(region).polygon();
    n.area = polygon_area(polygon);
    n.leaves = 0;
    double leaf_sum = 0.0;
    Rgb weighted = Rgb::Zero();
    for (int c : child_ids) {
      const LeafQuadtreeNode& child = nodes[static_cast<std::size_t>(c)];
      n.leaves += child.leaves;
      leaf_sum += child.area;
      weighted += child.area * child.mean;
    }
    n.mean = leaf_sum > 0.0 ? Rgb(weighted / leaf_sum) : Rgb::Zero();
    Rgb deviation = Rgb::Zero();
    for (int f : leaves)
      deviation += leaf_area[static_cast<std::size_t>(f)] *
                   (solution.face_radiosity[static_cast<std::size_t>(f)] - n.mean).abs();
    n.mean_deviation = leaf_sum > 0.0 ? Rgb(deviation / leaf_sum) : Rgb::Zero();
    // Rounding of the leaves' areas is ~1e-15 relative for meshes written in double precision; a
    // file rounded to floats is ~1e-7 off. A gap or an overlap larger than that is not a tiling.
    n.tiled = std::abs(leaf_sum - n.area) <= 1e-6 * n.area;
    return add_node(polygon, n);
  }
};

}  // namespace

LeafQuadtrees::LeafQuadtrees(const Scene& scene, const Solution& solution) {
  roots_.assign(scene.patches.size(), -1);
  std::vector<std::vector<int>> by_patch(scene.patches.size());
  for (std::size_t f = 0; f < solution.faces.size(); ++f)
    by_patch[static_cast<std::size_t>(solution.face_patch[f])].push_back(static_cast<int>(f));
  ElementHierarchy regions(scene);
  Builder b{solution, regions, nodes_, vertices_, children_, {}, {}, Vec3::Zero()};
  b.leaf_polygons.resize(solution.faces.size());
  b.leaf_area.resize(solution.faces.size());
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    for (int v : solution.faces[f]) b.leaf_polygons[f].push_back(solution.vertices[static_cast<std::size_t>(v)]);
    b.leaf_area[f] = polygon_area(b.leaf_polygons[f]);
  }
  nodes_.reserve(2 * solution.faces.size());
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    if (by_patch[p].empty()) continue;
    const Patch& patch = scene.patches[p];
    b.normal = patch.normal;
    // Within 1e-6 of the patch's size: covers vertices rounded to floats in a PLY.
    b.tolerance = 1e-6 * polygon_diameter(patch.vertices);
    roots_[p] = b.build(regions.root(static_cast<int>(p)), by_patch[p]);
  }
  unplaced_ = b.unplaced;
}

}  // namespace hrad::detail
