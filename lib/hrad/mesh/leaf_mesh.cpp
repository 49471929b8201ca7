// ElementHierarchy::to_solution(): the leaves as one conforming OpenMesh polygon mesh.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include "hrad/geometry/polygon.h"
#include "hrad/mesh/element_hierarchy.h"

namespace hrad {
namespace {

struct LeafMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using LeafMesh = OpenMesh::PolyMesh_ArrayKernelT<LeafMeshTraits>;

// Hash grid of points with cell size `cell`: welding within `tol` and searching points near a segment.
class PointGrid {
 public:
  PointGrid(double cell, double tol) : cell_(cell), tol_(tol) {}

  /// Id of a stored point within tol of p, or a new id.
  int weld(const Vec3& p) {
    const Key k = key(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = cells_.find(Key{k.x + dx, k.y + dy, k.z + dz});
          if (it == cells_.end()) continue;
          for (int id : it->second)
            if ((points_[static_cast<std::size_t>(id)] - p).norm() <= tol_) return id;
        }
    const int id = static_cast<int>(points_.size());
    points_.push_back(p);
    cells_[k].push_back(id);
    return id;
  }

  /// Ids of the points strictly inside segment (a, b) (farther than tol from both ends, within tol
  /// of the segment), sorted from a to b.
  std::vector<int> on_segment(int ia, int ib) const {
    const Vec3& a = points_[static_cast<std::size_t>(ia)];
    const Vec3& b = points_[static_cast<std::size_t>(ib)];
    const Vec3 d = b - a;
    const double len = d.norm();
    std::vector<std::pair<double, int>> found;
    if (len <= 2.0 * tol_) return {};
    // Walk the segment in steps of half a cell; the 27 cells around each step cover every point
    // within one cell of the segment.
    const int steps = static_cast<int>(std::ceil(len / (0.5 * cell_)));
    std::vector<Key> visited;
    for (int s = 0; s <= steps; ++s) {
      const Key k = key(a + d * (double(s) / steps));
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            const Key c{k.x + dx, k.y + dy, k.z + dz};
            if (std::find(visited.end() - std::min<std::ptrdiff_t>(visited.size(), 64), visited.end(), c) !=
                visited.end())
              continue;
            visited.push_back(c);
            auto it = cells_.find(c);
            if (it == cells_.end()) continue;
            for (int id : it->second) {
              if (id == ia || id == ib) continue;
              const Vec3& p = points_[static_cast<std::size_t>(id)];
              const double t = (p - a).dot(d) / (len * len);
              const double along = t * len;
              if (along <= tol_ || along >= len - tol_) continue;
              if ((a + t * d - p).norm() > tol_) continue;
              found.emplace_back(t, id);
            }
          }
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    std::vector<int> ids;
    for (const auto& f : found) ids.push_back(f.second);
    return ids;
  }

  const Vec3& point(int id) const { return points_[static_cast<std::size_t>(id)]; }

 private:
  struct Key {
    std::int64_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      return std::hash<std::int64_t>()(k.x * 73856093 ^ k.y * 19349663 ^ k.z * 83492791);
    }
  };
  Key key(const Vec3& p) const {
    return Key{static_cast<std::int64_t>(std::floor(p.x() / cell_)), static_cast<std::int64_t>(std::floor(p.y() / cell_)),
               static_cast<std::int64_t>(std::floor(p.z() / cell_))};
  }

  double cell_, tol_;
  std::vector<Vec3> points_;
  std::unordered_map<Key, std::vector<int>, KeyHash> cells_;
};

// Patches lying in one plane with the same front and the same material share vertices; others get
// their own copies. A change of material is a discontinuity of radiosity (the light set into the
// Cornell box ceiling): averaging across it would smear the emitter into its neighbours' vertices.
std::vector<int> plane_groups(const std::vector<ElementNode>& roots, double tol) {
  struct Plane {
    Vec3 normal;
    double offset;
    Rgb emission, reflectance;
  };
  std::vector<Plane> planes;
  std::vector<int> group(roots.size(), -1);
  for (std::size_t p = 0; p < roots.size(); ++p) {
    const Vec3 n = newell_normal(roots[p].polygon()).normalized();
    const double offset = n.dot(roots[p].vertices[0]);
    for (std::size_t g = 0; g < planes.size(); ++g) {
      if ((planes[g].normal - n).norm() <= 1e-9 && std::abs(planes[g].offset - offset) <= tol &&
          (planes[g].emission == roots[p].emission).all() && (planes[g].reflectance == roots[p].reflectance).all()) {
        group[p] = static_cast<int>(g);
        break;
      }
    }
    if (group[p] < 0) {
      group[p] = static_cast<int>(planes.size());
      planes.push_back({n, offset, roots[p].emission, roots[p].reflectance});
    }
  }
  return group;
}

}  // namespace

Solution ElementHierarchy::to_solution(double weld_tolerance, std::span<const std::array<Rgb, 9>> point_radiosity) const {
  Solution out;
  const std::vector<NodeId> leaf_ids = all_leaves();
  if (leaf_ids.empty()) return out;

  // Scale: bounding box of the roots, median leaf edge length for the grid cell.
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (int p = 0; p < patch_count_; ++p)
    for (const Vec3& v : node(root(p)).polygon()) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  const double diagonal = (hi - lo).norm();
  std::vector<double> edge_lengths;
  edge_lengths.reserve(leaf_ids.size());
  for (NodeId id : leaf_ids) edge_lengths.push_back((node(id).vertices[1] - node(id).vertices[0]).norm());
  // Welding merges corners that are one point up to rounding (~1e-16 of the coordinates), so 1e-9 of
  // the scene's diagonal is plenty, but never more than 1e-3 of the shortest leaf edge: a 1e-6 element
  // in a 1 km room (diagonal 1.7 km) collapsed to a point under a 1.7e-6 tolerance.
  const double shortest_edge = *std::min_element(edge_lengths.begin(), edge_lengths.end());
  const double tol =
      weld_tolerance > 0.0 ? weld_tolerance : std::min(1e-9 * diagonal, shortest_edge > 0.0 ? 1e-3 * shortest_edge : INFINITY);
  std::nth_element(edge_lengths.begin(), edge_lengths.begin() + edge_lengths.size() / 2, edge_lengths.end());
  const double cell = std::max(edge_lengths[edge_lengths.size() / 2], 4.0 * tol);

  // 1. Weld the leaves' corners into positions.
  PointGrid grid(cell, tol);
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
  const std::vector<int> group = plane_groups(roots, tol);
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
        value = 2.0 * (t - 0.5) * (t - 1.0) * v[static_cast<std::size_t>(k)] - 4.0 * t * (t - 1.0) * v[static_cast<std::size_t>(n + k)] +
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
