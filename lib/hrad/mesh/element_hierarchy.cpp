#include "hrad/mesh/element_hierarchy.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "hrad/geometry/polygon.h"
#include "hrad/mesh/detail/leaf_mesh.h"

namespace hrad {

ElementHierarchy::ElementHierarchy(const Scene& scene, double weld_tolerance)
    : patch_count_(static_cast<int>(scene.patches.size())) {
  nodes_.reserve(scene.patches.size());
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    const Patch& patch = scene.patches[p];
    assert(patch.vertices.size() == 3 || patch.vertices.size() == 4);
    ElementNode n;
    n.vertex_count = static_cast<int>(patch.vertices.size());
    std::copy(patch.vertices.begin(), patch.vertices.end(), n.vertices.begin());
    n.area = patch.area > 0.0 ? patch.area : polygon_area(n.polygon());
    n.patch = static_cast<int>(p);
    const Material& m = scene.material_of(patch);
    n.emission = m.emission;
    n.reflectance = m.reflectance;
    n.radiosity = m.emission;
    nodes_.push_back(n);
  }
  mesh_ = std::make_unique<detail::LeafMesh>(nodes_, weld_tolerance);
}

ElementHierarchy::~ElementHierarchy() = default;
ElementHierarchy::ElementHierarchy(ElementHierarchy&& other) noexcept = default;
ElementHierarchy& ElementHierarchy::operator=(ElementHierarchy&& other) noexcept = default;
ElementHierarchy::ElementHierarchy(const ElementHierarchy& other)
    : nodes_(other.nodes_),
      patch_count_(other.patch_count_),
      mesh_(other.mesh_ ? std::make_unique<detail::LeafMesh>(*other.mesh_) : nullptr) {}
ElementHierarchy& ElementHierarchy::operator=(const ElementHierarchy& other) {
  if (this != &other) *this = ElementHierarchy(other);
  return *this;
}

SplitKind split_kind_of(const ElementNode& n) {
  if (n.vertex_count != 4) return SplitKind::kQuadrants;
  const auto& v = n.vertices;
  // Lengths across the quad between its opposite edges' midpoints: along u (edge 3 to edge 1) and
  // along v (edge 0 to edge 2).
  const double along_u = ((v[1] + v[2]) - (v[3] + v[0])).norm();
  const double along_v = ((v[2] + v[3]) - (v[0] + v[1])).norm();
  if (along_u > kStripAspect * along_v) return SplitKind::kStripsU;
  if (along_v > kStripAspect * along_u) return SplitKind::kStripsV;
  return SplitKind::kQuadrants;
}

std::array<std::array<double, 2>, 4> quad_child_uv(SplitKind kind, int child) {
  const double a = 0.25 * child, b = 0.25 * (child + 1);
  switch (kind) {
    case SplitKind::kStripsU:
      return {{{a, 0.0}, {b, 0.0}, {b, 1.0}, {a, 1.0}}};
    case SplitKind::kStripsV:
      return {{{0.0, a}, {1.0, a}, {1.0, b}, {0.0, b}}};
    default: {
      // Parent corner k, the midpoint of edge k, the centre, the midpoint of edge k - 1.
      static constexpr double kCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      const double* c = kCorner[child];
      const double* n = kCorner[(child + 1) % 4];
      const double* p = kCorner[(child + 3) % 4];
      return {{{c[0], c[1]},
               {0.5 * (c[0] + n[0]), 0.5 * (c[1] + n[1])},
               {0.5, 0.5},
               {0.5 * (c[0] + p[0]), 0.5 * (c[1] + p[1])}}};
    }
  }
}

NodeId ElementHierarchy::split(NodeId id) {
  if (!node(id).is_leaf()) return node(id).first_child;
  const ElementNode parent = node(id);  // copy: push_back may reallocate
  // Neighbours that split a shared edge from either side get bit-identical points (midpoint()).
  const auto mid = detail::midpoint;
  const auto& v = parent.vertices;
  std::array<std::array<Vec3, 4>, 4> child{};
  int count = parent.vertex_count;
  const SplitKind kind = split_kind_of(parent);
  if (kind == SplitKind::kStripsU) {
    // Child k: u in [k/4, (k+1)/4], between the quarter points of edge 0 (v0 -> v1) and of edge 2
    // read from v3 to v2.
    for (int k = 0; k < 4; ++k)
      child[k] = {detail::quarter_point(v[0], v[1], k), detail::quarter_point(v[0], v[1], k + 1),
                  detail::quarter_point(v[3], v[2], k + 1), detail::quarter_point(v[3], v[2], k)};
  } else if (kind == SplitKind::kStripsV) {
    for (int k = 0; k < 4; ++k)
      child[k] = {detail::quarter_point(v[0], v[3], k), detail::quarter_point(v[1], v[2], k),
                  detail::quarter_point(v[1], v[2], k + 1), detail::quarter_point(v[0], v[3], k + 1)};
  } else if (count == 4) {
    const Vec3 c = (v[0] + v[1] + v[2] + v[3]) * 0.25;
    for (int k = 0; k < 4; ++k) {
      const int next = (k + 1) % 4, prev = (k + 3) % 4;
      child[k] = {v[k], mid(v[k], v[next]), c, mid(v[prev], v[k])};
    }
  } else {
    const Vec3 m01 = mid(v[0], v[1]), m12 = mid(v[1], v[2]), m20 = mid(v[2], v[0]);
    child[0] = {v[0], m01, m20, Vec3::Zero()};
    child[1] = {v[1], m12, m01, Vec3::Zero()};
    child[2] = {v[2], m20, m12, Vec3::Zero()};
    child[3] = {m01, m12, m20, Vec3::Zero()};
  }
  const NodeId first = static_cast<NodeId>(nodes_.size());
  for (int k = 0; k < 4; ++k) {
    ElementNode n;
    n.vertices = child[k];
    n.vertex_count = count;
    n.area = polygon_area(n.polygon());
    n.patch = parent.patch;
    n.parent = id;
    n.depth = parent.depth + 1;
    n.radiosity = parent.radiosity;
    n.emission = parent.emission;
    n.reflectance = parent.reflectance;
    nodes_.push_back(n);
  }
  node(id).first_child = first;
  node(id).split = kind;
  mesh_->split(id, first, kind);
  return first;
}

std::vector<NodeId> ElementHierarchy::leaves_below(NodeId id) const {
  std::vector<NodeId> out;
  std::vector<NodeId> stack{id};
  while (!stack.empty()) {
    const NodeId n = stack.back();
    stack.pop_back();
    const ElementNode& e = node(n);
    if (e.is_leaf()) {
      out.push_back(n);
    } else {
      for (int k = 3; k >= 0; --k) stack.push_back(e.first_child + k);
    }
  }
  return out;
}

std::vector<NodeId> ElementHierarchy::leaves(int patch) const { return leaves_below(root(patch)); }

std::vector<NodeId> ElementHierarchy::all_leaves() const {
  std::vector<NodeId> out;
  for (int p = 0; p < patch_count_; ++p) {
    const std::vector<NodeId> l = leaves(p);
    out.insert(out.end(), l.begin(), l.end());
  }
  return out;
}

void ElementHierarchy::subdivide_uniform(NodeId id, double max_area) {
  assert(max_area > 0.0);
  std::vector<NodeId> stack{id};
  while (!stack.empty()) {
    const NodeId n = stack.back();
    stack.pop_back();
    if (node(n).is_leaf() && !(node(n).area > max_area)) continue;
    const NodeId first = split(n);
    for (int k = 0; k < 4; ++k) stack.push_back(first + k);
  }
}

void ElementHierarchy::subdivide_uniform(double max_area) {
  for (int p = 0; p < patch_count_; ++p) subdivide_uniform(root(p), max_area);
}

void ElementHierarchy::pull_radiosity() {
  // Children always have larger ids than their parent: a reverse sweep is bottom-up.
  for (std::size_t i = nodes_.size(); i-- > 0;) {
    ElementNode& n = nodes_[i];
    if (n.is_leaf()) continue;
    Rgb sum = Rgb::Zero();
    double area = 0.0;
    for (int k = 0; k < 4; ++k) {
      const ElementNode& c = nodes_[static_cast<std::size_t>(n.first_child + k)];
      sum += c.area * c.radiosity;
      area += c.area;
    }
    n.radiosity = area > 0.0 ? Rgb(sum / area) : n.radiosity;
  }
}

}  // namespace hrad
