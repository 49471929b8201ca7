// The one iteration loop of every iterative solve: Jacobi iterations of gather (the link operators)
// and push-pull (HSA 1991 sec. 4, "SolveSystem"; each is a Jacobi step of classical radiosity),
// until SolverContext::record_iteration() says the estimated error is within the tolerance.
#pragma once

#include <span>

#include "hrad/solvers/link_operator.h"
#include "hrad/solvers/push_pull.h"
#include "hrad/solvers/solver_context.h"

namespace hrad {

/// Iterates from `field` (the caller times the phase) (radiosity set, e.g. by PushPull::make_field()). `bound` is the
/// largest radiosity a contracting iteration can reach (radiosity_bound()); passing twice it is reported as a failure
/// before anything overflows. Returns true when it converged.
bool iterate(SolverContext& ctx, const PushPull& push_pull, std::span<const LinkOperator* const> operators,
             NodeField& field, double bound);

/// Largest radiosity a closed scene can reach: with factors summing to at most 1 per element,
/// B <= E_max / (1 - rho_max) (the Neumann series of B = E + rho F B).
double radiosity_bound(const Scene& scene);

}  // namespace hrad
