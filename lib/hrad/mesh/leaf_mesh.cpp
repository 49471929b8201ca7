// ElementHierarchy::to_solution(): the leaves as one conforming OpenMesh polygon mesh.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include "hrad/mesh/element_hierarchy.h"
#include "hrad/mesh/leaf_geometry.h"

namespace hrad {
namespace {

struct LeafMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using LeafMesh = OpenMesh::PolyMesh_ArrayKernelT<LeafMeshTraits>;

}  // namespace

Solution ElementHierarchy::to_solution(double weld_tolerance,
                                       std::span<const std::array<Rgb, 9>> point_radiosity) const {
  Solution out;
  const std::vector<NodeId> leaf_ids = all_leaves();
  if (leaf_ids.empty()) return out;

  const auto [tol, cell] = detail::weld_scale(*this, leaf_ids, weld_tolerance);

  // 1. Weld the leaves' corners into positions.
  detail::PointGrid grid(cell, tol);
  std::vector<std::vector<int>> corners(leaf_ids.size());
  for (std::size_t f = 0; f < leaf_ids.size(); ++f)
    for (const Vec3& v : node(leaf_ids[f]).polygon()) corners[f].push_back(grid.weld(v));

  // 2. Insert T-vertices: every position lying inside a leaf edge becomes a vertex of that leaf.
  //    Each vertex of a leaf's polygon remembers its edge k and where along it (t from corner k).
  std::vector<std::vector<int>> polygons(leaf_ids.size());
  std::vector<std::vector<std::pair<int, double>>> along(leaf_ids.size());
  for (std::size_t f = 0; f < leaf_ids.size(); ++f) {
    const std::vector<int>& c = corners[f];
    for (std::size_t k = 0; k < c.size(); ++k) {
      const int a = c[k], b = c[(k + 1) % c.size()];
      if (a == b) continue;  // collapsed corner (element smaller than the weld tolerance)
      polygons[f].push_back(a);
      along[f].emplace_back(static_cast<int>(k), 0.0);
      const Vec3 pa = grid.point(a), ab = grid.point(b) - pa;
      for (int t : grid.on_segment(a, b)) {
        polygons[f].push_back(t);
        along[f].emplace_back(static_cast<int>(k), (grid.point(t) - pa).dot(ab) / ab.squaredNorm());
      }
    }
  }

  // 3. One vertex per (plane group, position).
  std::vector<ElementNode> roots(nodes_.begin(), nodes_.begin() + patch_count_);
  const std::vector<int> group = detail::plane_groups(roots, tol);
  std::map<std::pair<int, int>, int> vertex_of;  // (group, position) -> key index
  std::vector<int> key_position;
  std::vector<std::vector<int>> face_keys(leaf_ids.size());
  for (std::size_t f = 0; f < leaf_ids.size(); ++f) {
    const int g = group[static_cast<std::size_t>(node(leaf_ids[f]).patch)];
    for (int pos : polygons[f]) {
      auto [it, inserted] = vertex_of.try_emplace({g, pos}, static_cast<int>(key_position.size()));
      if (inserted) key_position.push_back(pos);
      face_keys[f].push_back(it->second);
    }
  }

  // 4. The OpenMesh half-edge mesh. A face that would make an edge non-manifold (overlapping or
  //    folded input) gets its own copies of its vertices, so the mesh stays a valid half-edge mesh.
  LeafMesh mesh;
  std::vector<LeafMesh::VertexHandle> handle_of_key(key_position.size());
  std::vector<int> key_of_vertex;
  auto add_vertex = [&](int key) {
    const Vec3& p = grid.point(key_position[static_cast<std::size_t>(key)]);
    const LeafMesh::VertexHandle vh = mesh.add_vertex(LeafMesh::Point(p.x(), p.y(), p.z()));
    key_of_vertex.push_back(key);
    return vh;
  };
  for (std::size_t k = 0; k < key_position.size(); ++k) handle_of_key[k] = add_vertex(static_cast<int>(k));
  const bool om_errors = omerr().is_enabled();
  omerr().disable();  // complex-edge messages are handled below
  out.faces.resize(leaf_ids.size());
  std::vector<std::size_t> face_leaf;  // OpenMesh face index -> leaf index (degenerate leaves are left out)
  std::vector<std::vector<LeafMesh::VertexHandle>> face_vertices(leaf_ids.size());
  for (std::size_t f = 0; f < leaf_ids.size(); ++f) {
    std::vector<LeafMesh::VertexHandle> vhs;
    for (int key : face_keys[f]) vhs.push_back(handle_of_key[static_cast<std::size_t>(key)]);
    LeafMesh::FaceHandle fh;
    if (vhs.size() >= 3) fh = mesh.add_face(vhs);
    if (!fh.is_valid() && vhs.size() >= 3) {
      for (std::size_t k = 0; k < vhs.size(); ++k) vhs[k] = add_vertex(face_keys[f][k]);
      fh = mesh.add_face(vhs);
    }
    if (fh.is_valid()) face_leaf.push_back(f);
    for (const LeafMesh::VertexHandle& vh : vhs) out.faces[f].push_back(vh.idx());
    face_vertices[f] = vhs;
  }
  if (om_errors) omerr().enable();

  // 5. Vertex radiosity: area-weighted mean of the faces around each (group, position), counting
  //    the larger face a T-vertex was inserted into (anchoring; Baum et al. 1991).
  //    With point_radiosity, each leaf contributes its own value at the vertex.
  std::vector<Rgb> sum(key_position.size(), Rgb::Zero());
  std::vector<double> weight(key_position.size(), 0.0);
  for (const LeafMesh::FaceHandle fh : mesh.faces()) {
    const std::size_t f = face_leaf[static_cast<std::size_t>(fh.idx())];
    const NodeId id = leaf_ids[f];
    const ElementNode& e = node(id);
    for (std::size_t j = 0; j < face_vertices[f].size(); ++j) {
      const int key = key_of_vertex[static_cast<std::size_t>(face_vertices[f][j].idx())];
      Rgb value = e.radiosity;
      if (!point_radiosity.empty()) {
        // The leaf's quadratic along edge k through corner k, the edge's midpoint and corner k + 1.
        const std::array<Rgb, 9>& v = point_radiosity[static_cast<std::size_t>(id)];
        const auto [k, t] = along[f][j];
        const int n = e.vertex_count;
        value = 2.0 * (t - 0.5) * (t - 1.0) * v[static_cast<std::size_t>(k)] -
                4.0 * t * (t - 1.0) * v[static_cast<std::size_t>(n + k)] +
                2.0 * t * (t - 0.5) * v[static_cast<std::size_t>((k + 1) % n)];
      }
      sum[static_cast<std::size_t>(key)] += e.area * value;
      weight[static_cast<std::size_t>(key)] += e.area;
    }
  }

  out.vertices.resize(mesh.n_vertices());
  out.vertex_radiosity.resize(mesh.n_vertices());
  for (const LeafMesh::VertexHandle vh : mesh.vertices()) {
    const LeafMesh::Point& p = mesh.point(vh);
    const std::size_t i = static_cast<std::size_t>(vh.idx());
    out.vertices[i] = Vec3(p[0], p[1], p[2]);
    const int key = key_of_vertex[i];
    out.vertex_radiosity[i] = weight[static_cast<std::size_t>(key)] > 0.0
                                  ? Rgb(sum[static_cast<std::size_t>(key)] / weight[static_cast<std::size_t>(key)])
                                  : Rgb::Zero();
  }

  out.face_patch.resize(leaf_ids.size());
  out.face_radiosity.resize(leaf_ids.size());
  std::vector<Rgb> patch_sum(static_cast<std::size_t>(patch_count_), Rgb::Zero());
  std::vector<double> patch_area(static_cast<std::size_t>(patch_count_), 0.0);
  for (std::size_t f = 0; f < leaf_ids.size(); ++f) {
    const ElementNode& e = node(leaf_ids[f]);
    out.face_patch[f] = e.patch;
    out.face_radiosity[f] = e.radiosity;
    patch_sum[static_cast<std::size_t>(e.patch)] += e.area * e.radiosity;
    patch_area[static_cast<std::size_t>(e.patch)] += e.area;
  }
  out.patch_radiosity.resize(static_cast<std::size_t>(patch_count_));
  for (std::size_t p = 0; p < patch_sum.size(); ++p)
    out.patch_radiosity[p] = patch_area[p] > 0.0 ? Rgb(patch_sum[p] / patch_area[p]) : Rgb::Zero();
  return out;
}

}  // namespace hrad
