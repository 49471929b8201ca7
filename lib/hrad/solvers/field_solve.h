// Linear elements over dense field links (field_links.h): Jacobi iterations of gather and push-pull
// with the linear basis (push_pull.h: each leaf the L2 projection of E + rho H onto its linear
// space), then the solution with the leaves' corner values. Shared by the full matrix and
// substructuring; the corner values are the unknowns, so there is no dense direct solve.
#pragma once

#include <cstddef>

#include "hrad/core/solution.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/field_links.h"
#include "hrad/solvers/solver_context.h"

namespace hrad {

/// Iterates to ctx's tolerance (the "solve" phase), stores the radiosity in `h` and finishes the
/// summary with `factors` interactions.
SolveSummary solve_linear_field(SolverContext& ctx, ElementHierarchy& h, const FieldLinks& links, std::size_t factors,
                                Solution* out);

}  // namespace hrad
