// What a hierarchical solve can hand on besides its Solution: the element hierarchy with the
// radiosity of every node (leaves: B; interior elements: the area mean of their leaves), the
// cluster tree above it, and the links. A final gather through the links (gather/link_gather.h)
// reads them, so that a gather after a solve in the same process does not derive them again.
#pragma once

#include <memory>
#include <vector>

#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/cluster_tree.h"
#include "hrad/solvers/refine.h"

namespace hrad {

struct SolvedHierarchy {
  std::unique_ptr<ElementHierarchy> hierarchy;
  std::unique_ptr<ClusterTree> tree;  ///< null when the solve did not cluster
  /// Every link of the last refinement. Cluster radiosities are not kept: a gather reads a
  /// cluster's patches (their roots' radiosity).
  LinkVector links;
};

}  // namespace hrad
