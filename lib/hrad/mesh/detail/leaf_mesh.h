// The leaves of an ElementHierarchy as the faces of one OpenMesh half-edge mesh (Botsch, Steinberg,
// Bischoff & Kobbelt 2002, "OpenMesh: a generic and efficient polygon mesh data structure"), refined
// in place: a 1-to-4 split of a leaf cuts its face into its four children's faces (quadrants, or
// strips across a long quad). A face's loop holds
// its leaf's corners and, between them, the corners of finer neighbours lying on its edges (its
// T-vertices): an edge already split by the neighbour across it offers its points to the second
// split, and a split of an edge puts its new points into the neighbour's loop too. So edge neighbours,
// T-vertices and the vertices shared by leaves of neighbouring patches are the half-edge structure's.
// Internal to the mesh module (it is not installed: OpenMesh stays private to hrad_mesh).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "hrad/mesh/element_hierarchy.h"

namespace hrad::detail {

struct LeafMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;  // doubles: a 1e-6 element 1 km from the origin keeps its corners
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<LeafMeshTraits>;

// The midpoint of a and b as every split computes it: (a + b) * 0.5 is the same bits as
// (b + a) * 0.5, so the neighbour across an edge, splitting it from the other end, gets the same
// point.
inline Vec3 midpoint(const Vec3& a, const Vec3& b) { return (a + b) * 0.5; }

// The point at t = k/4 (k = 0..4) of the segment a -> b, by midpoints only (the same bits from
// either end, as midpoint()).
inline Vec3 quarter_point(const Vec3& a, const Vec3& b, int k) {
  const auto mid = midpoint;
  switch (k) {
    case 0:
      return a;
    case 1:
      return mid(a, mid(a, b));
    case 2:
      return mid(a, b);
    case 3:
      return mid(mid(a, b), b);
    default:
      return b;
  }
}

class LeafMesh {
 public:
  /// The roots (nodes 0 .. patches - 1) as faces. Their corners are welded by position once, here
  /// (within `weld_tolerance`, or for 0 1e-9 of the bounding-box diagonal but at most 1e-3 of the
  /// shortest patch edge), and a welded corner lying inside another patch's edge becomes a vertex of
  /// that patch's face, so patches meeting at T-junctions or creases are half-edge neighbours. A
  /// patch whose face would make an edge non-manifold (overlapping input) gets its own vertices.
  LeafMesh(const std::vector<ElementNode>& roots, double weld_tolerance);

  /// Cuts the face of leaf `id` into the faces of its children first .. first + 3, as `kind`
  /// (ElementHierarchy::split()'s corner order). A leaf without a face (a degenerate patch) has
  /// children without faces.
  void split(NodeId id, NodeId first, SplitKind kind);

  /// True when an edge of leaf `id` holds two or more corners of finer leaves of its plane group
  /// across it: a neighbour at least two levels finer (the restricted quadtree's test).
  bool crowded(NodeId id) const;

  const PolyMesh& mesh() const { return mesh_; }
  /// The face of a leaf (invalid for interior nodes and leaves of degenerate patches).
  PolyMesh::FaceHandle face(NodeId id) const {
    return PolyMesh::FaceHandle(face_of_node_[static_cast<std::size_t>(id)]);
  }
  NodeId node_of(PolyMesh::FaceHandle f) const { return mesh_.property(node_of_face_, f); }
  /// The halfedge of `id`'s face leaving its corner 0.
  PolyMesh::HalfedgeHandle first_halfedge(NodeId id) const;
  /// Corner k's vertex of node `id`.
  PolyMesh::VertexHandle corner(NodeId id, int k) const {
    return PolyMesh::VertexHandle(corners_[static_cast<std::size_t>(id)][static_cast<std::size_t>(k)]);
  }
  /// The plane group of node `id`'s patch: patches in one plane with one front and one material form
  /// a group; the output mesh shares a vertex only among the faces of one group (leaf_geometry.h
  /// plane_groups()).
  int group_of_node(NodeId id) const { return group_of_node_[static_cast<std::size_t>(id)]; }
  Vec3 position(PolyMesh::VertexHandle v) const {
    const PolyMesh::Point& p = mesh_.point(v);
    return Vec3(p[0], p[1], p[2]);
  }

 private:
  PolyMesh::HalfedgeHandle halfedge_from(PolyMesh::FaceHandle f, PolyMesh::VertexHandle v) const;
  PolyMesh::HalfedgeHandle halfedge_to(PolyMesh::FaceHandle f, PolyMesh::VertexHandle v) const;
  bool in_loop(PolyMesh::FaceHandle f, PolyMesh::VertexHandle v) const;
  PolyMesh::VertexHandle edge_point(PolyMesh::FaceHandle f, PolyMesh::VertexHandle a, PolyMesh::VertexHandle b,
                                    const Vec3& at);
  PolyMesh::VertexHandle midpoint(PolyMesh::FaceHandle f, PolyMesh::VertexHandle a, PolyMesh::VertexHandle b);
  void split_strips(NodeId id, NodeId first, SplitKind kind, const std::array<PolyMesh::VertexHandle, 4>& c);
  PolyMesh::HalfedgeHandle cut(PolyMesh::FaceHandle f, PolyMesh::VertexHandle a, PolyMesh::VertexHandle b);
  void set_node(NodeId id, PolyMesh::FaceHandle f, const std::array<PolyMesh::VertexHandle, 4>& corners);

  PolyMesh mesh_;
  OpenMesh::FPropHandleT<NodeId> node_of_face_;
  std::vector<int> face_of_node_;            // per node: its face's index while a leaf, else -1
  std::vector<std::array<int, 4>> corners_;  // per node: its corners' vertex indices (-1 without a face)
  std::vector<int> group_of_node_;           // per node: its patch's plane group
  double tolerance_ = 0.0;
};

}  // namespace hrad::detail
