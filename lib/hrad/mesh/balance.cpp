// ElementHierarchy::balance(): the restricted quadtree (at most one level between edge neighbours).
#include "hrad/mesh/detail/leaf_mesh.h"
#include "hrad/mesh/element_hierarchy.h"

namespace hrad {

std::size_t ElementHierarchy::balance() {
  std::size_t splits = 0;
  while (true) {
    // A neighbour one level finer puts one corner inside an edge (its midpoint); two or more corners
    // inside an edge mean a neighbour at least two levels finer. Leaves of other planes meet only
    // along creases, where the output mesh gives each side its own vertices: they do not count.
    std::vector<NodeId> coarse;
    for (const NodeId id : all_leaves())
      if (mesh_->crowded(id)) coarse.push_back(id);
    if (coarse.empty()) break;
    for (const NodeId id : coarse) split(id);
    splits += coarse.size();
  }
  return splits;
}

}  // namespace hrad
