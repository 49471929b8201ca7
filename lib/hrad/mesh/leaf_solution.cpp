// ElementHierarchy::to_solution(): the half-edge mesh's leaves copied out as one Solution.
#include <cstdint>
#include <unordered_map>

#include "hrad/mesh/detail/leaf_mesh.h"
#include "hrad/mesh/element_hierarchy.h"

namespace hrad {

Solution ElementHierarchy::to_solution(std::span<const std::array<Rgb, 9>> point_radiosity) const {
  using detail::PolyMesh;
  Solution out;
  const std::vector<NodeId> leaf_ids = all_leaves();
  if (leaf_ids.empty()) return out;
  const PolyMesh& mesh = mesh_->mesh();

  // Each face's loop from corner 0; a vertex is one output vertex per plane group (creases give
  // each side its own copy), numbered as first met. Each vertex of a loop remembers its edge k and
  // where along it (t from corner k), for point_radiosity's quadratic along the edge.
  struct Along {
    int edge;
    double t;
  };
  std::unordered_map<std::uint64_t, int> output_vertex;  // (mesh vertex, plane group) -> index
  output_vertex.reserve(mesh.n_vertices() + mesh.n_vertices() / 8);
  std::vector<std::vector<Along>> along(leaf_ids.size());
  out.faces.resize(leaf_ids.size());
  auto add_output_vertex = [&](const Vec3& p) {
    out.vertices.push_back(p);
    return static_cast<int>(out.vertices.size() - 1);
  };
  for (std::size_t f = 0; f < leaf_ids.size(); ++f) {
    const NodeId id = leaf_ids[f];
    const ElementNode& e = node(id);
    const PolyMesh::FaceHandle fh = mesh_->face(id);
    if (!fh.is_valid()) {  // a patch smaller than the weld tolerance: its own vertices
      for (int k = 0; k < e.vertex_count; ++k) {
        out.faces[f].push_back(add_output_vertex(e.vertices[static_cast<std::size_t>(k)]));
        along[f].push_back({k, 0.0});
      }
      continue;
    }
    const std::uint64_t group = static_cast<std::uint32_t>(mesh_->group_of_node(id));
    const int n = e.vertex_count;
    const PolyMesh::HalfedgeHandle start = mesh_->first_halfedge(id);
    PolyMesh::HalfedgeHandle h = start;
    int k = 0;
    do {
      const PolyMesh::VertexHandle v = mesh.from_vertex_handle(h);
      const Vec3 p = mesh_->position(v);
      if (v == mesh_->corner(id, (k + 1) % n) && h != start) ++k;
      const Vec3 a = mesh_->position(mesh_->corner(id, k));
      const Vec3 ab = mesh_->position(mesh_->corner(id, (k + 1) % n)) - a;
      const double t = v == mesh_->corner(id, k) ? 0.0 : (p - a).dot(ab) / ab.squaredNorm();
      const auto [it, inserted] = output_vertex.try_emplace(static_cast<std::uint64_t>(v.idx()) << 32 | group,
                                                            static_cast<int>(out.vertices.size()));
      if (inserted) add_output_vertex(p);
      out.faces[f].push_back(it->second);
      along[f].push_back({k, t});
      h = mesh.next_halfedge_handle(h);
    } while (h != start);
  }

  // Vertex radiosity: area-weighted mean of the faces around each output vertex, counting the
  // larger face a T-vertex lies in (anchoring; Baum et al. 1991). With point_radiosity, each leaf
  // contributes its own value at the vertex.
  std::vector<Rgb> sum(out.vertices.size(), Rgb::Zero());
  std::vector<double> weight(out.vertices.size(), 0.0);
  for (std::size_t f = 0; f < leaf_ids.size(); ++f) {
    const NodeId id = leaf_ids[f];
    const ElementNode& e = node(id);
    for (std::size_t j = 0; j < out.faces[f].size(); ++j) {
      const std::size_t v = static_cast<std::size_t>(out.faces[f][j]);
      Rgb value = e.radiosity;
      if (!point_radiosity.empty()) {
        // The leaf's quadratic along edge k through corner k, the edge's midpoint and corner k + 1.
        const std::array<Rgb, 9>& b = point_radiosity[static_cast<std::size_t>(id)];
        const auto [k, t] = along[f][j];
        const int n = e.vertex_count;
        value = 2.0 * (t - 0.5) * (t - 1.0) * b[static_cast<std::size_t>(k)] -
                4.0 * t * (t - 1.0) * b[static_cast<std::size_t>(n + k)] +
                2.0 * t * (t - 0.5) * b[static_cast<std::size_t>((k + 1) % n)];
      }
      sum[v] += e.area * value;
      weight[v] += e.area;
    }
  }
  out.vertex_radiosity.resize(out.vertices.size());
  for (std::size_t v = 0; v < out.vertices.size(); ++v)
    out.vertex_radiosity[v] = weight[v] > 0.0 ? Rgb(sum[v] / weight[v]) : Rgb::Zero();

  out.face_patch.resize(leaf_ids.size());
  out.face_radiosity.resize(leaf_ids.size());
  out.face_irradiance.resize(leaf_ids.size());
  std::vector<Rgb> patch_sum(static_cast<std::size_t>(patch_count_), Rgb::Zero());
  std::vector<double> patch_area(static_cast<std::size_t>(patch_count_), 0.0);
  for (std::size_t f = 0; f < leaf_ids.size(); ++f) {
    const ElementNode& e = node(leaf_ids[f]);
    out.face_patch[f] = e.patch;
    out.face_radiosity[f] = e.radiosity;
    out.face_irradiance[f] = e.gathered;
    patch_sum[static_cast<std::size_t>(e.patch)] += e.area * e.radiosity;
    patch_area[static_cast<std::size_t>(e.patch)] += e.area;
  }
  out.patch_radiosity.resize(static_cast<std::size_t>(patch_count_));
  for (std::size_t p = 0; p < patch_sum.size(); ++p)
    out.patch_radiosity[p] = patch_area[p] > 0.0 ? Rgb(patch_sum[p] / patch_area[p]) : Rgb::Zero();
  return out;
}

}  // namespace hrad
