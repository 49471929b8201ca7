// Hierarchical radiosity: Hanrahan, Salzman & Aupperle 1991, "A rapid hierarchical radiosity
// algorithm" (SIGGRAPH '91; "HSA" below).
//
// One quadtree per input patch (ElementHierarchy). Every pair of patches is refined into links
// (Refine, HSA sec. 3): a pair whose factors are both below the tolerance, and whose visibility is
// known well enough, becomes a link gathered both ways; otherwise the larger element is split 1-to-4
// and its children are refined against the other, never below the smallest element area aeps.
// The links are solved by Jacobi iterations of gather (over links) and push-pull (over each tree)
// until the largest relative change is below SolveOptions::tolerance. With --bfeps the links are
// re-refined with the current radiosity after each solve (HSA sec. 4.2) until nothing changes.
// Partly visible pairs refine further while F times the visibility error exceeds the tolerance;
// pairs facing away or fully hidden get no link.
//
// Defaults (SolveOptions: feps and bfeps 0 = unused, aeps 0 = automatic). Both are unit-
// independent: feps is a pure number, aeps a fraction of the scene's total area. With neither
// --feps nor --bfeps, feps = kAutoFeps. They were chosen by sweeps (feps 0.1 .. 0.001, aeps
// total/20000 .. total/500) on cornell_box.obj (mm) and a closed 4 x 2.5 x 5 box:
//   * feps 0.02, aeps total/2000 (the lecture's kind of setting): Cornell box in ~2 s, but a closed
//     box at rho = 0.9 is 9% off on whole walls: an element inherits its ancestors' average factors
//     (a corner element's sum to 1.24 instead of 1), and at rho = 0.9 that bias is amplified;
//   * smaller aeps makes this worse (more corner elements linked through coarse ancestors) and
//     costs more; smaller feps makes it better: feps 0.005 with aeps total/500 puts every wall of
//     the box within 0.4% at rho = 0.9 (elements within 5%), and the Cornell box solves in ~2.5 s
//     (2 cores) with every patch within 2% (of the brighter of the patch and the mean reflector
//     radiosity) of the full matrix with similar elements (~500).
// There is no automatic bfeps: B*F refinement (HSA sec. 4.2) is used when --bfeps is given.
#pragma once

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/solvers/solve.h"

namespace hrad {

/// Form-factor tolerance used when neither --feps nor --bfeps is given.
inline constexpr double kAutoFeps = 0.01;
/// Smallest element area when --aeps is 0: this fraction of the scene's total area.
inline constexpr double kAutoAepsFraction = 1.0 / 1000.0;
/// BF refinement re-refines after each solve at most this many times (HSA sec. 4.2).
inline constexpr int kMaxRefinePasses = 8;

/// The tolerances a hierarchical solve uses after the automatic defaults are applied.
struct HierarchicalTolerances {
  double feps = 0.0;   ///< form-factor tolerance (0 = not used)
  double bfeps = 0.0;  ///< B*F tolerance in radiosity units (0 = not used)
  double aeps = 0.0;   ///< smallest element area (scene units squared), > 0
};

/// Applies the defaults: feps = kAutoFeps when both feps and bfeps are 0; aeps = kAutoAepsFraction
/// times the total area when aeps is 0.
HierarchicalTolerances hierarchical_tolerances(const Scene& scene, const SolveOptions& options);

/// Solves `scene` by hierarchical radiosity (options.method is ignored) and writes the leaves to
/// `out` (if not null). Summary: links counts directed links (each stored interaction is gathered
/// both ways and counts twice, as the n^2 of the full matrix counts both directions); figures
/// "feps", "bfeps", "aeps", "refine_passes", "link_pairs", "min_element_area", "max_depth".
SolveSummary solve_hierarchical(const Scene& scene, const SolveOptions& options, Solution* out);

}  // namespace hrad
