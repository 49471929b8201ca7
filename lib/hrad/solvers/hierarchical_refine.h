// Refinement of element pairs into links for hierarchical radiosity (HSA 1991, "Refine").
#pragma once

#include <cstddef>
#include <vector>

#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/form_factor_evaluator.h"

namespace hrad::detail {

/// A pair of elements under consideration, with its estimate once evaluated (re-refinement
/// passes reuse the estimate of an existing link instead of calling the kernel again).
struct RefineCandidate {
  NodeId p = kNoNode;
  NodeId q = kNoNode;
  bool evaluated = false;
  FormFactorEstimate estimate;  ///< receiver p, source q
};

/// A stored interaction between p and q: p gathers from q with estimate.value = F(p -> q) and q
/// gathers from p with estimate.reverse = F(q -> p).
using LinkPair = RefineCandidate;

struct RefineTolerances {
  double feps = 0.0;   ///< 0 = no form-factor test
  double bfeps = 0.0;  ///< 0 = no B*F test
  double aeps = 0.0;   ///< a node is split only when its children's area stays >= aeps
};

struct RefineResult {
  std::vector<LinkPair> links;
  std::size_t splits = 0;      ///< split decisions taken (new or existing children)
  std::size_t new_nodes = 0;   ///< nodes the hierarchy grew by
  std::size_t dropped = 0;     ///< pairs facing away, hidden or coplanar: no link
};

/// Refines `work` breadth-first: all unevaluated candidates of one level are estimated in
/// parallel (each estimate is deterministic), then decided sequentially in order (splits happen
/// only there), so the result does not depend on the thread count. `channels` selects which
/// radiosity channels the B*F test looks at (1 or 3).
RefineResult refine_pairs(ElementHierarchy& hierarchy, const FormFactorEvaluator& evaluator,
                          std::vector<RefineCandidate> work, const RefineTolerances& tolerances, int channels);

/// True when the pair must be refined further under `tolerances` (HSA 1991 Refine; BF variant of
/// sec. 4.2), using the current radiosity of p and q for the B*F test.
bool pair_needs_refinement(const ElementHierarchy& hierarchy, const RefineCandidate& pair,
                           const RefineTolerances& tolerances, int channels);

}  // namespace hrad::detail
