// A quadtree over each patch's leaves of a Solution, with what a Barnes-Hut gather needs at every
// node: its polygon, the area-weighted mean radiosity of its leaves and how far they deviate from
// it. A SOLUTION.ply carries the leaves, not the solver's tree, so the tree is rebuilt from the
// patch polygon by the element hierarchy's own 1-to-4 split (mesh/element_hierarchy.h), each leaf
// going into the child region that contains it. A leaf that no child contains (a mesh not made by
// those splits) stays with the node as a child of its own, so every leaf is reached whatever the
// mesh; a node is `tiled` when its leaves cover its polygon (their areas add up to its area), and
// only a tiled node may stand in for its leaves as one polygon.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/core/types.h"

namespace hrad::detail {

/// Regions are split at most this often (a patch split 40 times has leaves 2^-80 of its area,
/// deeper than any mesh hrad makes); leaves below that depth hang from the deepest region.
inline constexpr int kLeafQuadtreeMaxDepth = 40;

struct LeafQuadtreeNode {
  std::uint32_t first_vertex = 0;  ///< the node's polygon: LeafQuadtrees::vertices()[first_vertex, + vertex_count)
  std::uint32_t vertex_count = 0;
  std::uint32_t first_child = 0;  ///< children: LeafQuadtrees::children()[first_child, + child_count)
  std::uint32_t child_count = 0;
  int leaf = -1;             ///< the Solution face of a leaf node; -1 for a region
  std::uint32_t leaves = 1;  ///< leaves at or below
  double area = 0.0;
  /// Area-weighted mean of the leaves' face_radiosity.
  Rgb mean = Rgb::Zero();
  /// Area-weighted mean of |B_j - mean| over the leaves j, per channel (0 for a leaf).
  Rgb mean_deviation = Rgb::Zero();
  bool tiled = true;  ///< the leaves cover the polygon (always true for a leaf)
  bool is_leaf() const { return leaf >= 0; }
};

class LeafQuadtrees {
 public:
  /// One tree per patch of `scene` over `solution`'s leaves (face_patch must index scene.patches).
  LeafQuadtrees(const Scene& scene, const Solution& solution);

  /// The root of a patch's tree, or -1 when the solution has no leaf on it.
  int root(int patch) const { return roots_[static_cast<std::size_t>(patch)]; }
  const LeafQuadtreeNode& node(int id) const { return nodes_[static_cast<std::size_t>(id)]; }
  std::size_t size() const { return nodes_.size(); }
  std::span<const Vec3> polygon(int id) const {
    const LeafQuadtreeNode& n = node(id);
    return {vertices_.data() + n.first_vertex, n.vertex_count};
  }
  std::span<const int> children(int id) const {
    const LeafQuadtreeNode& n = node(id);
    return {children_.data() + n.first_child, n.child_count};
  }
  /// Leaves that sit directly under a region because no child region contains them.
  std::size_t unplaced_leaves() const { return unplaced_; }

 private:
  std::vector<LeafQuadtreeNode> nodes_;
  std::vector<Vec3> vertices_;
  std::vector<int> children_;
  std::vector<int> roots_;
  std::size_t unplaced_ = 0;
};

}  // namespace hrad::detail
