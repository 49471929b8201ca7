// The geometry that builds the leaf mesh from the patches, once (leaf_mesh.cpp): welding the
// patches' corners into positions, finding the positions inside a patch's edge (T-junctions between
// patches), and the plane groups whose leaves share output vertices. Internal to the mesh module (not
// installed).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "hrad/geometry/polygon.h"
#include "hrad/mesh/element_hierarchy.h"

namespace hrad::detail {

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
    return Key{static_cast<std::int64_t>(std::floor(p.x() / cell_)),
               static_cast<std::int64_t>(std::floor(p.y() / cell_)),
               static_cast<std::int64_t>(std::floor(p.z() / cell_))};
  }

  double cell_, tol_;
  std::vector<Vec3> points_;
  std::unordered_map<Key, std::vector<int>, KeyHash> cells_;
};

// Patches lying in one plane with the same front and the same material share vertices; others get
// their own copies. A change of material is a discontinuity of radiosity (the light set into the
// Cornell box ceiling): averaging across it would smear the emitter into its neighbours' vertices.
inline std::vector<int> plane_groups(const std::vector<ElementNode>& roots, double tol) {
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

/// The weld tolerance and grid cell for the patches' polygons `roots` (not empty): `weld_tolerance`,
/// or 0 for 1e-9 of their bounding-box diagonal but never more than 1e-3 of the shortest patch edge
/// (a 1e-6 patch in a 1 km room, diagonal 1.7 km, collapsed to a point under 1.7e-6); the cell is the
/// median patch edge (welding merges corners that are one point up to rounding, ~1e-16 of the
/// coordinates).
inline std::pair<double, double> weld_scale(const std::vector<ElementNode>& roots, double weld_tolerance) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  std::vector<double> edge_lengths;
  edge_lengths.reserve(roots.size() * 4);
  for (const ElementNode& r : roots)
    for (int k = 0; k < r.vertex_count; ++k) {
      const Vec3& v = r.vertices[static_cast<std::size_t>(k)];
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
      const double length = (r.vertices[static_cast<std::size_t>((k + 1) % r.vertex_count)] - v).norm();
      if (length > 0.0) edge_lengths.push_back(length);
    }
  const double diagonal = (hi - lo).norm();
  if (edge_lengths.empty()) edge_lengths.push_back(diagonal > 0.0 ? diagonal : 1.0);
  const double shortest_edge = *std::min_element(edge_lengths.begin(), edge_lengths.end());
  const double tol = weld_tolerance > 0.0 ? weld_tolerance : std::min(1e-9 * diagonal, 1e-3 * shortest_edge);
  std::nth_element(edge_lengths.begin(), edge_lengths.begin() + edge_lengths.size() / 2, edge_lengths.end());
  return {tol, std::max(edge_lengths[edge_lengths.size() / 2], 4.0 * tol)};
}

}  // namespace hrad::detail
