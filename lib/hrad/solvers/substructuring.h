// Substructuring (Cohen, Greenberg, Immel & Brock 1986, "An efficient radiosity approach for
// realistic image synthesis"): coarse patches shoot, fine elements receive. Element i gathers
// B_i = E_i + rho_i * sum_P F(i -> P) B_P over the n x N element-to-patch factors, and a patch's
// radiosity is the area average of its elements; iterated (Gauss-Seidel over patches) to the tolerance.
#pragma once

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/solvers/solve.h"

namespace hrad {

/// Patches: the input polygons, or their uniform subdivision to area <= options.patch_area;
/// elements: each patch subdivided to area <= max_area. Summary: links = n * N; figures
/// "max_area", "patch_area", "shooting_patches". options.method is ignored.
SolveSummary solve_substructuring(const Scene& scene, const SolveOptions& options, Solution* out);

}  // namespace hrad
