// ElementHierarchy::balance(): the restricted quadtree (at most one level between edge neighbours).
#include <map>

#include "hrad/mesh/element_hierarchy.h"
#include "hrad/mesh/leaf_geometry.h"

namespace hrad {

std::size_t ElementHierarchy::balance(double weld_tolerance) {
  std::vector<ElementNode> roots(nodes_.begin(), nodes_.begin() + patch_count_);
  std::size_t splits = 0;
  while (true) {
    const std::vector<NodeId> leaf_ids = all_leaves();
    if (leaf_ids.empty()) break;
    const auto [tol, cell] = detail::weld_scale(*this, leaf_ids, weld_tolerance);
    const std::vector<int> group = detail::plane_groups(roots, tol);
    // The corners of each plane group's leaves (leaves of other planes meet only along creases,
    // where the output mesh gives each side its own vertices).
    std::map<int, detail::PointGrid> grids;
    std::vector<std::array<int, 4>> corners(leaf_ids.size());
    for (std::size_t f = 0; f < leaf_ids.size(); ++f) {
      const ElementNode& e = node(leaf_ids[f]);
      detail::PointGrid& grid = grids.try_emplace(group[static_cast<std::size_t>(e.patch)], cell, tol).first->second;
      for (int k = 0; k < e.vertex_count; ++k)
        corners[f][static_cast<std::size_t>(k)] = grid.weld(e.vertices[static_cast<std::size_t>(k)]);
    }
    // A neighbour one level finer puts one corner inside an edge (its midpoint); two or more corners
    // inside an edge mean a neighbour at least two levels finer.
    std::vector<NodeId> coarse;
    for (std::size_t f = 0; f < leaf_ids.size(); ++f) {
      const ElementNode& e = node(leaf_ids[f]);
      const detail::PointGrid& grid = grids.at(group[static_cast<std::size_t>(e.patch)]);
      for (int k = 0; k < e.vertex_count; ++k) {
        const int a = corners[f][static_cast<std::size_t>(k)],
                  b = corners[f][static_cast<std::size_t>((k + 1) % e.vertex_count)];
        if (a != b && grid.on_segment(a, b).size() > 1) {
          coarse.push_back(leaf_ids[f]);
          break;
        }
      }
    }
    if (coarse.empty()) break;
    for (const NodeId id : coarse) split(id);
    splits += coarse.size();
  }
  return splits;
}

}  // namespace hrad
