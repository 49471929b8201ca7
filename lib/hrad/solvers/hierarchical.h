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
//
// Defaults (SolveOptions says 0 = automatic). All are unit-independent: factors are pure numbers,
// bfeps is relative to the brightest emission, aeps to the scene's total area. They were chosen by
// sweeps on the bundled scenes (cornell_box.obj in mm, simple_room.obj in m) and the closed-room
// tests (tests/solvers/hierarchical_test.cpp): each is the coarsest setting that keeps
//   * every element of a closed room with uniform E and rho = 0.9 within 1% of E / (1 - rho), and
//   * every Cornell-box patch within a few percent of the full-matrix answer at its default,
// while the Cornell box solves in about a second.
#pragma once

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/solvers/solve.h"

namespace hrad {

/// Form-factor tolerance used when neither --feps nor --bfeps is given.
inline constexpr double kAutoFeps = 0.005;
/// B*F tolerance when only --bfeps mode is wanted with an automatic value: this fraction of the
/// largest emission of any channel (not used unless SolveOptions::bfeps < 0 is ever allowed; kept
/// for the report and the sweeps).
inline constexpr double kAutoBfepsFraction = 0.002;
/// Smallest element area when --aeps is 0: this fraction of the scene's total area.
inline constexpr double kAutoAepsFraction = 1.0 / 500.0;
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
