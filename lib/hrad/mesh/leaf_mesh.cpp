// detail::LeafMesh: the leaves as the faces of one OpenMesh half-edge mesh, cut in place by splits.
#include "hrad/mesh/detail/leaf_mesh.h"

// GCC 12 reports OpenMesh's property arrays (PropertyT::push_back of a default VectorT, which is
// uninitialized by design) as maybe used uninitialized once inlined here; silenced for this file.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <cassert>

#include <OpenMesh/Core/System/omstream.hh>

#include "hrad/mesh/detail/leaf_geometry.h"

namespace hrad::detail {
namespace {

using VertexHandle = PolyMesh::VertexHandle;
using HalfedgeHandle = PolyMesh::HalfedgeHandle;
using FaceHandle = PolyMesh::FaceHandle;

PolyMesh::Point point_of(const Vec3& p) { return PolyMesh::Point(p.x(), p.y(), p.z()); }

// Whether OpenMesh can add the face `loop` to `mesh`: its vertices distinct, each on the boundary
// (or isolated), each of its edges new or a boundary half-edge, and where two consecutive old edges
// are not yet consecutive, a free gap around their vertex for add_face() to re-link the patch
// between them into (its own walk over the vertex's half-edges, done here first: on a
// non-manifold neighbourhood, slivers beside a welded corner, the walk meets a half-edge without
// a successor and OpenMesh 9 asserts instead of failing). Otherwise the face takes vertices of its own.
bool adds_cleanly(const PolyMesh& mesh, const std::vector<VertexHandle>& loop) {
  const std::size_t n = loop.size();
  std::vector<HalfedgeHandle> h(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j)
      if (loop[i] == loop[j]) return false;
    if (!mesh.is_boundary(loop[i])) return false;
    h[i] = mesh.find_halfedge(loop[i], loop[(i + 1) % n]);
    if (h[i].is_valid() && !mesh.is_boundary(h[i])) return false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const HalfedgeHandle inner_prev = h[i], inner_next = h[(i + 1) % n];
    if (!inner_prev.is_valid() || !inner_next.is_valid() || mesh.next_halfedge_handle(inner_prev) == inner_next)
      continue;
    HalfedgeHandle gap = mesh.opposite_halfedge_handle(inner_next);
    for (std::size_t steps = 0;; ++steps) {
      const HalfedgeHandle next = mesh.next_halfedge_handle(gap);
      if (!next.is_valid() || steps > mesh.n_halfedges()) return false;
      gap = mesh.opposite_halfedge_handle(next);
      if (mesh.is_boundary(gap)) break;
    }
    if (gap == inner_prev || !mesh.next_halfedge_handle(gap).is_valid() ||
        !mesh.next_halfedge_handle(inner_prev).is_valid() || !mesh.prev_halfedge_handle(inner_next).is_valid())
      return false;
  }
  return true;
}

}  // namespace

LeafMesh::LeafMesh(const std::vector<ElementNode>& roots, double weld_tolerance) {
  mesh_.add_property(node_of_face_);
  face_of_node_.assign(roots.size(), -1);
  corners_.assign(roots.size(), {-1, -1, -1, -1});
  if (roots.empty()) return;
  const auto [tol, cell] = weld_scale(roots, weld_tolerance);
  tolerance_ = tol;
  group_of_node_ = plane_groups(roots, tol);

  // One weld of all patches' corners (creases included: floor and wall share the edge they meet
  // along, so a split on one side puts its midpoint into the other side's loop).
  PointGrid grid(cell, tol);
  std::vector<std::array<int, 4>> welded(roots.size());
  for (std::size_t p = 0; p < roots.size(); ++p)
    for (int k = 0; k < roots[p].vertex_count; ++k)
      welded[p][static_cast<std::size_t>(k)] = grid.weld(roots[p].vertices[static_cast<std::size_t>(k)]);
  std::vector<VertexHandle> vertex_of_position;
  auto vertex = [&](int position) {
    if (static_cast<std::size_t>(position) >= vertex_of_position.size())
      vertex_of_position.resize(static_cast<std::size_t>(position) + 1);
    VertexHandle& v = vertex_of_position[static_cast<std::size_t>(position)];
    if (!v.is_valid()) v = mesh_.add_vertex(point_of(grid.point(position)));
    return v;
  };

  const bool om_errors = omerr().is_enabled();
  omerr().disable();  // complex edges (overlapping input) are handled below
  for (std::size_t p = 0; p < roots.size(); ++p) {
    const int n = roots[p].vertex_count;
    const std::array<int, 4>& c = welded[p];
    bool distinct = true;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        distinct = distinct && c[static_cast<std::size_t>(i)] != c[static_cast<std::size_t>(j)];
    if (!distinct) continue;  // a patch smaller than the weld tolerance: no face, no neighbours
    // The loop: each corner, then the welded positions inside the edge to the next (T-junctions).
    std::vector<int> loop;
    std::vector<int> corner_at;  // index into loop of corner k
    for (int k = 0; k < n; ++k) {
      const int a = c[static_cast<std::size_t>(k)], b = c[static_cast<std::size_t>((k + 1) % n)];
      corner_at.push_back(static_cast<int>(loop.size()));
      loop.push_back(a);
      for (int t : grid.on_segment(a, b)) loop.push_back(t);
    }
    std::vector<VertexHandle> vhs;
    for (int position : loop) vhs.push_back(vertex(position));
    FaceHandle f = adds_cleanly(mesh_, vhs) ? mesh_.add_face(vhs) : FaceHandle();
    if (!f.is_valid()) {
      for (std::size_t k = 0; k < vhs.size(); ++k) vhs[k] = mesh_.add_vertex(point_of(grid.point(loop[k])));
      f = mesh_.add_face(vhs);
    }
    if (!f.is_valid()) continue;
    std::array<VertexHandle, 4> corners;
    for (int k = 0; k < n; ++k)
      corners[static_cast<std::size_t>(k)] = vhs[static_cast<std::size_t>(corner_at[static_cast<std::size_t>(k)])];
    set_node(static_cast<NodeId>(p), f, corners);
  }
  if (om_errors) omerr().enable();
}

void LeafMesh::set_node(NodeId id, FaceHandle f, const std::array<VertexHandle, 4>& corners) {
  const std::size_t i = static_cast<std::size_t>(id);
  face_of_node_[i] = f.idx();
  for (std::size_t k = 0; k < 4; ++k) corners_[i][k] = corners[k].idx();
  if (f.is_valid()) mesh_.property(node_of_face_, f) = id;
}

HalfedgeHandle LeafMesh::halfedge_from(FaceHandle f, VertexHandle v) const {
  for (const HalfedgeHandle h : mesh_.fh_range(f))
    if (mesh_.from_vertex_handle(h) == v) return h;
  assert(false && "vertex not in the face's loop");
  return HalfedgeHandle();
}

HalfedgeHandle LeafMesh::halfedge_to(FaceHandle f, VertexHandle v) const {
  for (const HalfedgeHandle h : mesh_.fh_range(f))
    if (mesh_.to_vertex_handle(h) == v) return h;
  assert(false && "vertex not in the face's loop");
  return HalfedgeHandle();
}

bool LeafMesh::in_loop(FaceHandle f, VertexHandle v) const {
  for (const HalfedgeHandle h : mesh_.fh_range(f))
    if (mesh_.to_vertex_handle(h) == v) return true;
  return false;
}

HalfedgeHandle LeafMesh::first_halfedge(NodeId id) const { return halfedge_from(face(id), corner(id, 0)); }

// The vertex at `at` (a point of the face's edge from corner a to corner b): a vertex of the loop
// between them (the neighbour across split that edge already), or a new vertex inserted into the
// edge, which puts it into the neighbour's loop as well.
VertexHandle LeafMesh::edge_point(FaceHandle f, VertexHandle a, VertexHandle b, const Vec3& at) {
  const Vec3 pa = position(a), pb = position(b);
  const Vec3 d = pb - pa;
  const double tol = std::min(tolerance_, 1e-3 * d.norm());
  HalfedgeHandle h = halfedge_from(f, a);
  for (HalfedgeHandle g = h; mesh_.to_vertex_handle(g) != b; g = mesh_.next_halfedge_handle(g))
    if ((position(mesh_.to_vertex_handle(g)) - at).norm() <= tol) return mesh_.to_vertex_handle(g);
  // The piece of the edge holding the point (T-vertices from input T-junctions may lie anywhere).
  const double t = (at - pa).dot(d);
  while (mesh_.to_vertex_handle(h) != b && (position(mesh_.to_vertex_handle(h)) - pa).dot(d) < t)
    h = mesh_.next_halfedge_handle(h);
  const VertexHandle m = mesh_.add_vertex(point_of(at));
  mesh_.split(mesh_.edge_handle(h), m);
  return m;
}

// The midpoint as ElementHierarchy::split() computes it: bit-identical from either side.
VertexHandle LeafMesh::midpoint(FaceHandle f, VertexHandle a, VertexHandle b) {
  return edge_point(f, a, b, detail::midpoint(position(a), position(b)));
}

// Inserts the edge a -> b across face f (both in its loop, not adjacent); returns its halfedge.
HalfedgeHandle LeafMesh::cut(FaceHandle f, VertexHandle a, VertexHandle b) {
  return mesh_.insert_edge(halfedge_to(f, a), halfedge_from(f, b));
}

void LeafMesh::split(NodeId id, NodeId first, SplitKind kind) {
  const FaceHandle f = face(id);
  const std::size_t parent = static_cast<std::size_t>(id);
  const std::size_t end = static_cast<std::size_t>(first) + 4;
  if (end > face_of_node_.size()) {
    face_of_node_.resize(end, -1);
    corners_.resize(end, {-1, -1, -1, -1});
    group_of_node_.resize(end, -1);
  }
  for (std::size_t i = static_cast<std::size_t>(first); i < end; ++i) group_of_node_[i] = group_of_node_[parent];
  if (!f.is_valid()) return;
  const int n = corners_[parent][3] < 0 ? 3 : 4;
  std::array<VertexHandle, 4> c, m;
  for (int k = 0; k < n; ++k) c[static_cast<std::size_t>(k)] = corner(id, k);
  if (n == 4 && kind != SplitKind::kQuadrants) {
    split_strips(id, first, kind, c);
    return;
  }
  for (int k = 0; k < n; ++k)
    m[static_cast<std::size_t>(k)] =
        midpoint(f, c[static_cast<std::size_t>(k)], c[static_cast<std::size_t>((k + 1) % n)]);
  face_of_node_[parent] = -1;

  // The four child faces, each told apart by the one parent corner its loop holds (the middle
  // triangle holds none).
  std::array<FaceHandle, 4> faces;
  auto other = [&](HalfedgeHandle h, VertexHandle v) {  // the face of the cut holding v, else the other
    const FaceHandle a = mesh_.face_handle(h), b = mesh_.opposite_face_handle(h);
    return in_loop(a, v) ? a : b;
  };
  if (n == 4) {
    const HalfedgeHandle across = cut(f, m[0], m[2]);
    const FaceHandle side1 = other(across, c[1]);
    const FaceHandle side3 =
        mesh_.face_handle(across) == side1 ? mesh_.opposite_face_handle(across) : mesh_.face_handle(across);
    const Vec3 centre = (position(c[0]) + position(c[1]) + position(c[2]) + position(c[3])) * 0.25;
    const VertexHandle mc = mesh_.add_vertex(point_of(centre));
    mesh_.split(mesh_.edge_handle(across), mc);
    const HalfedgeHandle h1 = cut(side1, mc, m[1]);
    const HalfedgeHandle h3 = cut(side3, mc, m[3]);
    const std::array<FaceHandle, 4> quadrants{mesh_.face_handle(h1), mesh_.opposite_face_handle(h1),
                                              mesh_.face_handle(h3), mesh_.opposite_face_handle(h3)};
    for (const FaceHandle g : quadrants)
      for (int k = 0; k < 4; ++k)
        if (in_loop(g, c[static_cast<std::size_t>(k)])) faces[static_cast<std::size_t>(k)] = g;
    for (int k = 0; k < 4; ++k) {
      const std::size_t i = static_cast<std::size_t>(k);
      set_node(first + k, faces[i], {c[i], m[i], mc, m[(i + 3) % 4]});
    }
  } else {
    const HalfedgeHandle h0 = cut(f, m[0], m[2]);
    const FaceHandle rest0 = other(h0, c[1]);
    const HalfedgeHandle h1 = cut(rest0, m[1], m[0]);
    const FaceHandle rest1 = other(h1, c[2]);
    const HalfedgeHandle h2 = cut(rest1, m[2], m[1]);
    faces[0] = other(h0, c[0]);
    faces[1] = other(h1, c[1]);
    faces[2] = other(h2, c[2]);
    faces[3] = faces[2] == mesh_.face_handle(h2) ? mesh_.opposite_face_handle(h2) : mesh_.face_handle(h2);
    const VertexHandle none;
    set_node(first + 0, faces[0], {c[0], m[0], m[2], none});
    set_node(first + 1, faces[1], {c[1], m[1], m[0], none});
    set_node(first + 2, faces[2], {c[2], m[2], m[1], none});
    set_node(first + 3, faces[3], {m[0], m[1], m[2], none});
  }
}

// Four strips across the long direction (ElementHierarchy::split()): the quarter points L_k of one
// long edge and R_k of the other (L_0, R_0 at the strips' start), cut L_k -> R_k for k = 1, 2, 3.
void LeafMesh::split_strips(NodeId id, NodeId first, SplitKind kind, const std::array<VertexHandle, 4>& c) {
  const FaceHandle f = face(id);
  const bool u = kind == SplitKind::kStripsU;
  // Strips across u run from edge 0 (c0 -> c1) and edge 2 (c3 -> c2, the loop runs c2 -> c3); across v
  // from edge 3 (c0 -> c3, the loop runs c3 -> c0) and edge 1 (c1 -> c2).
  const VertexHandle l0 = c[0], l4 = u ? c[1] : c[3], r0 = u ? c[3] : c[1], r4 = c[2];
  std::array<VertexHandle, 5> l, r;
  l[0] = l0, l[4] = l4, r[0] = r0, r[4] = r4;
  const Vec3 pl0 = position(l0), pl4 = position(l4), pr0 = position(r0), pr4 = position(r4);
  for (int k = 1; k < 4; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    l[i] = u ? edge_point(f, l0, l4, quarter_point(pl0, pl4, k)) : edge_point(f, l4, l0, quarter_point(pl0, pl4, k));
    r[i] = u ? edge_point(f, r4, r0, quarter_point(pr0, pr4, k)) : edge_point(f, r0, r4, quarter_point(pr0, pr4, k));
  }
  face_of_node_[static_cast<std::size_t>(id)] = -1;
  FaceHandle rest = f;
  std::array<FaceHandle, 4> faces;
  for (std::size_t k = 1; k < 4; ++k) {
    const HalfedgeHandle h = cut(rest, l[k], r[k]);
    const FaceHandle a = mesh_.face_handle(h), b = mesh_.opposite_face_handle(h);
    rest = in_loop(a, l4) ? a : b;
    faces[k - 1] = rest == a ? b : a;
  }
  faces[3] = rest;
  for (std::size_t k = 0; k < 4; ++k) {
    const std::array<VertexHandle, 4> corners = u ? std::array<VertexHandle, 4>{l[k], l[k + 1], r[k + 1], r[k]}
                                                  : std::array<VertexHandle, 4>{l[k], r[k], r[k + 1], l[k + 1]};
    set_node(first + static_cast<NodeId>(k), faces[k], corners);
  }
}

bool LeafMesh::crowded(NodeId id) const {
  const FaceHandle f = face(id);
  if (!f.is_valid()) return false;
  const int group = group_of_node_[static_cast<std::size_t>(id)];
  const int n = corners_[static_cast<std::size_t>(id)][3] < 0 ? 3 : 4;
  // Is v a corner of a leaf of this plane group across the piece of edge h?
  auto corner_across = [&](HalfedgeHandle h, VertexHandle v) {
    const FaceHandle g = mesh_.opposite_face_handle(h);
    if (!g.is_valid()) return false;
    const std::size_t other = static_cast<std::size_t>(node_of(g));
    if (group_of_node_[other] != group) return false;
    for (const int c : corners_[other])
      if (c == v.idx()) return true;
    return false;
  };
  const HalfedgeHandle start = first_halfedge(id);
  HalfedgeHandle h = start;
  int k = 0, inside = 0;  // the edge from corner k; corners of finer leaves inside it so far
  do {
    const VertexHandle v = mesh_.to_vertex_handle(h);
    const HalfedgeHandle next = mesh_.next_halfedge_handle(h);
    if (v == corner(id, (k + 1) % n)) {
      k = k + 1;
      inside = 0;
    } else if ((corner_across(h, v) || corner_across(next, v)) && ++inside > 1) {
      return true;
    }
    h = next;
  } while (h != start);
  return false;
}

}  // namespace hrad::detail
