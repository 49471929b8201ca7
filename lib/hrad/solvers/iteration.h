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

/// The stopping measure of one iteration (SolveOptions::tolerance), the larger of two relative
/// changes: the largest change of a leaf's radiosity over the largest reflected radiosity |B - E|
/// (max norm), and the change integrated over the leaves' areas over the reflected power (the
/// area-weighted L1 norm, in which a Jacobi step contracts by at most rho_max where the factors
/// are reciprocal and sum to at most 1, and whose error is the power-balance's). The max norm alone
/// is loose where a small leaf is far brighter than the rest (the wall under a lamp 1 mm away, ~1000x
/// brighter than the room's other walls: 3.6e-4 of the reflected power was left unconverged at a
/// tolerance of 1e-6: LampNearWall.TheStoppingTestBoundsTheReflectedPowerBesideABrightFootprint).
/// The change itself when nothing is reflected yet; NaN when it is not finite (record_iteration()
/// then reports a failure).
double stopping_change(const LeafChange& change);

/// Largest radiosity a closed scene can reach: with factors summing to at most 1 per element,
/// B <= E_max / (1 - rho_max) (the Neumann series of B = E + rho F B).
double radiosity_bound(const Scene& scene);

}  // namespace hrad
