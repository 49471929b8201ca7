// The element hierarchy: one quadtree per patch, stored in one arena of nodes addressed by index,
// beside one OpenMesh half-edge mesh whose faces are the current leaves (mesh/detail/leaf_mesh.h):
// a split cuts the leaf's face in place, so edge neighbours, T-vertices and vertices shared across
// patches are the mesh's, from the first split to the output. Solvers refine it (uniformly for full
// matrix and substructuring, adaptively for hierarchical radiosity) and keep their per-element
// unknowns in the nodes; to_solution() copies the mesh out as a Solution (no OpenMesh type crosses
// this header).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/core/types.h"

namespace hrad {

namespace detail {
class LeafMesh;
}

/// Index of a node in ElementHierarchy's arena. Stable across split() (the arena only grows).
using NodeId = std::int32_t;
inline constexpr NodeId kNoNode = -1;

/// How ElementHierarchy::split() cuts a node. A quad whose length between one pair of opposite edges
/// exceeds kStripAspect times its length between the other pair is cut across the long direction
/// into four strips (kStripsU: u in [k/4, (k+1)/4] of its map x(u, v), simpson_rule.h; kStripsV:
/// v), so that repeated splits bring any element within kStripAspect : 1; every other node is cut
/// into quadrants, which keep the parent's shape (the quadtree of Hanrahan, Salzman & Aupperle
/// 1991). A very long element puts its quadrature points and its constant (or linear) radiosity far
/// from where a nearby kernel peaks along it (a corridor's wall beside its end wall). Quadrants halve
/// both directions, and the field may vary across an element's width as much as along it: the 14 : 1
/// sides of RenderPark's office2 lamp housings are lit on their lower part only, and cut into strips
/// they left the housings' tops 32% too bright at aeps total/4000 (quadrants: 19%).
enum class SplitKind : std::uint8_t { kQuadrants, kStripsU, kStripsV };
inline constexpr double kStripAspect = 16.0;

/// One element: a convex planar triangle or quad lying on one patch.
struct ElementNode {
  std::array<Vec3, 4> vertices{};           ///< counter-clockwise seen from the patch's front; [3] unused for triangles
  int vertex_count = 0;                     ///< 3 or 4
  SplitKind split = SplitKind::kQuadrants;  ///< how the children cut it (kQuadrants for a leaf)
  double area = 0.0;
  int patch = -1;  ///< index into Scene::patches
  NodeId parent = kNoNode;
  NodeId first_child = kNoNode;  ///< the 4 children are first_child .. first_child + 3; kNoNode for a leaf
  int depth = 0;                 ///< 0 for a patch's root

  Rgb radiosity = Rgb::Zero();    ///< B: the unknown, per channel
  Rgb emission = Rgb::Zero();     ///< E: the patch's emission (copied down at construction and split)
  Rgb reflectance = Rgb::Zero();  ///< rho: the patch's reflectance
  /// H: a leaf's irradiance (the mean over it of what its links gathered) in the solve's last
  /// gather, so that B = E + rho H; the net flux leaving it is B - H (radiant exchange).
  Rgb gathered = Rgb::Zero();

  bool is_leaf() const { return first_child == kNoNode; }
  std::span<const Vec3> polygon() const { return {vertices.data(), static_cast<std::size_t>(vertex_count)}; }
};

/// How split() cuts `n` (SplitKind; a triangle is kQuadrants: its four children at its edge midpoints).
SplitKind split_kind_of(const ElementNode& n);

/// The corners, in the parent's (u, v) (simpson_rule.h kSimpsonQuadUv), of child k of a quad split
/// as `kind`, in the child's vertex order: the child's own bilinear map is the parent's on that
/// rectangle of (u, v).
std::array<std::array<double, 2>, 4> quad_child_uv(SplitKind kind, int child);

/// Arena of quadtrees. Node i < scene.patches.size() is the root of patch i (root(patch) == patch);
/// children are appended in blocks of 4. Not thread-safe for split(); reading nodes and writing
/// their radiosity fields from several threads is fine as long as each thread owns its nodes.
class ElementHierarchy {
 public:
  /// One root per patch of `scene`, with the patch's polygon, area, emission and reflectance.
  /// Radiosity starts at the emission; gathered at 0. The roots' corners are welded into the mesh's
  /// vertices once, here: `weld_tolerance` (scene units; 0 = 1e-9 times the scene's bounding-box
  /// diagonal, at most 1e-3 of the shortest patch edge) decides when two corners are one vertex and
  /// when a corner lies on another patch's edge.
  explicit ElementHierarchy(const Scene& scene, double weld_tolerance = 0.0);
  ~ElementHierarchy();
  ElementHierarchy(const ElementHierarchy& other);
  ElementHierarchy& operator=(const ElementHierarchy& other);
  ElementHierarchy(ElementHierarchy&& other) noexcept;
  ElementHierarchy& operator=(ElementHierarchy&& other) noexcept;

  std::size_t size() const { return nodes_.size(); }
  int patch_count() const { return patch_count_; }
  NodeId root(int patch) const { return static_cast<NodeId>(patch); }
  const ElementNode& node(NodeId id) const { return nodes_[static_cast<std::size_t>(id)]; }
  ElementNode& node(NodeId id) { return nodes_[static_cast<std::size_t>(id)]; }
  const std::vector<ElementNode>& nodes() const { return nodes_; }

  /// Splits a leaf 1-to-4 and returns its first child; returns the existing first child if `id`
  /// is already split. A quad is split by split_kind_of(): into quadrants at its edge midpoints and
  /// its vertex mean (child k keeps parent vertex k as its vertex k), or into four strips at the
  /// quarter points of its two long edges (child k spans quad_child_uv(kind, k)). A triangle is split
  /// at its edge midpoints (the middle child is the triangle of the three midpoints). Children
  /// inherit emission, reflectance and radiosity; their areas sum to the parent's (to rounding);
  /// each child is counter-clockwise as its parent. The leaf's face is cut in place; a point of an
  /// edge the neighbour across has split already is its vertex, otherwise the new point joins the
  /// neighbour's face as its T-vertex.
  NodeId split(NodeId id);

  /// The leaves of one patch's tree in depth-first order (children in index order).
  std::vector<NodeId> leaves(int patch) const;
  /// The leaves of all trees: patch by patch, each in leaves(patch) order. This is the face order
  /// of to_solution().
  std::vector<NodeId> all_leaves() const;
  /// The leaves below (or equal to) `id`, depth-first.
  std::vector<NodeId> leaves_below(NodeId id) const;

  /// Splits every leaf whose area exceeds `max_area` until none does (max_area > 0).
  void subdivide_uniform(double max_area);
  /// The same for the tree below `id` only.
  void subdivide_uniform(NodeId id, double max_area);

  /// Balances the leaves as a restricted quadtree (Von Herzen & Barr 1987; Baum, Mann, Smith &
  /// Winget 1991 sec. 4): splits every leaf one of whose edges holds two or more corners of the
  /// leaves across it in its plane group (a neighbour at least two levels finer; read off the
  /// face's half-edge loop), until none does. Then each leaf edge holds at most one T-vertex, so the
  /// output mesh has no long T-edges. Splits across patches too (coplanar patches of one material
  /// meeting at T-junctions). Returns the splits.
  std::size_t balance();

  /// Sets each interior node's radiosity to the area average of its children, bottom-up
  /// (the "pull" of push-pull; Hanrahan, Salzman & Aupperle 1991, sec. 4).
  void pull_radiosity();

  /// The leaves as one conforming polygon mesh, copied from the half-edge mesh:
  ///  * faces are the leaves in all_leaves() order, each its face's loop from corner 0, with
  ///    face_patch and face_radiosity;
  ///  * T-vertices (a leaf vertex lying on the open edge of a larger neighbouring leaf, on the same
  ///    patch or across patches that meet there) are in that leaf's loop, so every leaf vertex lying
  ///    on another leaf's edge is a vertex of that leaf's polygon: no cracks;
  ///  * vertices are shared by the faces that lie in one plane; where the plane changes (a crease,
  ///    e.g. floor and wall) each side keeps its own copy of the vertex, so colours do not bleed
  ///    around corners;
  ///  * vertex_radiosity is the area-weighted mean of the leaves around the vertex (including the
  ///    larger leaf a T-vertex was inserted into): Baum, Mann, Smith & Winget 1991, "Making radiosity
  ///    usable: automatic preprocessing and meshing techniques for the generation of accurate
  ///    radiosity solutions" (anchoring of T-vertices, sec. 4), so smooth display shows no cracks;
  ///  * patch_radiosity is the area-weighted mean of each patch's leaves.
  ///
  /// `point_radiosity`, when not empty, holds per node (by id) a leaf's radiosity at the corner,
  /// edge-midpoint and centre points of formfactor/simpson_rule.h (a solver that knows B to second
  /// order over each leaf); a leaf then contributes its value at the vertex to the vertex's mean (at
  /// a T-vertex, the quadratic along the edge through its ends and midpoint) instead of its
  /// constant.
  Solution to_solution(std::span<const std::array<Rgb, 9>> point_radiosity = {}) const;

 private:
  std::vector<ElementNode> nodes_;
  int patch_count_ = 0;
  std::unique_ptr<detail::LeafMesh> mesh_;
};

}  // namespace hrad
