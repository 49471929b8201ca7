// Substructuring (Cohen, Greenberg, Immel & Brock 1986, "An efficient radiosity approach for
// realistic image synthesis"): coarse patches shoot, fine elements receive. Element i gathers
// B_i = E_i + rho_i * sum_P F(i -> P) B_P over the n x N element-to-patch factors, and a patch's
// radiosity is the area average of its elements; iterated (Gauss-Seidel over patches) to the tolerance.
// With linear elements each element gathers a field from each patch (field_links.h), reading the
// patch's radiosity moments pulled up from its elements.
#pragma once

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/solvers/solve.h"

namespace hrad {

/// Shooting-patch area when options.patch_area is 0: this fraction of the scene's total area.
/// On the Cornell box with the published floor (cornell_box_uncut_floor.obj, 24 input polygons, 492
/// elements at the default max_area) against the full matrix at its defaults, the worst per-patch
/// difference is 60% with the input polygons as patches (the whole floor shoots its mean radiosity
/// at the block sides beside it),
/// 7.3% at total/64 (123 patches, 2.4 s) and 5.3% at total/128 (297 patches, 4.9 s, slower than the
/// full matrix): total/64 keeps nN four times below n^2 and every patch within a few percent.
inline constexpr double kAutoPatchAreaFraction = 1.0 / 64.0;

/// Patches: the uniform subdivision of the input polygons to area <= options.patch_area (0 =
/// kAutoPatchAreaFraction of the total area; the largest input area keeps the input polygons);
/// elements: each patch subdivided to area <= max_area. Summary: links = n * N; figures
/// "max_area", "patch_area", "shooting_patches". options.method is ignored.
SolveSummary solve_substructuring(const Scene& scene, const SolveOptions& options, Solution* out);

}  // namespace hrad
