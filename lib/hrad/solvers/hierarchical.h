// Hierarchical radiosity: Hanrahan, Salzman & Aupperle 1991, "A rapid hierarchical radiosity
// algorithm" (SIGGRAPH '91; "HSA" below).
//
// One quadtree per input patch (ElementHierarchy). Every pair of patches is refined into links
// (Refine, HSA sec. 3): a pair whose error is below the tolerance becomes a link gathered both
// ways; otherwise the element over which the factor varies more is split 1-to-4 and its children
// are refined against the other, never below the smallest element area aeps. Pairs facing away or
// fully hidden get no link. The links are solved by Jacobi iterations of gather and push-pull
// until the largest relative change is below SolveOptions::tolerance. With --bfeps the links are
// re-refined with the current radiosity after each solve (HSA sec. 4.2) until nothing changes.
//
// Two departures from HSA, both about the error of a link (HSA sec. 4; Lischinski, Smits &
// Greenberg 1994, "Bounds and error estimates for radiosity"; Holzschuch & Sillion 1998, "An
// exhaustive error-bounding algorithm for hierarchical radiosity"):
//  * The oracle (hierarchical_refine.h) tests the error a link makes, not the size of its factor:
//    how far the point-to-element factor strays, over the sample points of each element, from the
//    average the link gives them, weighted by the source's a-priori radiosity relative to the
//    scene's (1 in a closed uniform room; ~40-70 for the Cornell box's light, 0.74 for its white
//    walls). HSA's test F > feps refines a large floor against a small light by F's average, which
//    hides that points under the light see it with a much larger factor. Partly visible pairs
//    refine while a shadow boundary could make a point's error as large as its unoccluded factor,
//    or while the sampled visibility's error exceeds feps.
//  * Push and pull (hierarchical_leaf_factors.h) resolve each link to the leaves on both sides
//    with the leaves' own factors, scaled to the link's exact exchange, instead of giving every
//    leaf below the receiver the receiver's average factor and gathering the source's area mean:
//    each leaf's factors then sum to 1 in a closed room up to quadrature (HSA's summed from 0.8 to
//    1.24 on corner elements, which put them 5% off at rho = 0.9 and can make Jacobi diverge as
//    rho -> 1), and each leaf's emitted power is conserved (HSA conserve it per patch only: 1.5%
//    of a tiny light's power went missing in a 1 km room lit unevenly).
//
// Defaults (SolveOptions: feps and bfeps 0 = unused, aeps 0 = automatic). Both are unit-
// independent: feps is a pure number, aeps a fraction of the scene's total area. With neither
// --feps nor --bfeps, feps = kAutoFeps. Measured (Release, 2 cores shared with other jobs, so
// seconds are +-50%; a scratch driver over solve(); worst = largest |B / (E / (1 - rho)) - 1|):
//  * closed rooms at the defaults, rho = 0.5 / 0.9 / 0.99 / 0.999 (0.999 converges in ~6900
//    iterations, within the default max_iterations):
//      4 x 2.5 x 5 box             worst 5e-7 / 8e-6 / 1e-4 / 1e-3  (384 elements, 22464 links)
//      the same with T-junctions   worst 8e-7 / 8e-6 / 1e-4 / 1e-3  (432 elements)
//      faceted sphere, 48 facets   worst 3e-5 / 5e-5 / 1e-4 / 1e-3  (576 elements)
//    From rho = 0.9 on this is the stopping test's share (tolerance 1e-6 leaves ~1e-6 / (1 - rho)).
//    HSA's push with their oracle (feps 0.005, aeps total/500) left the box 2.2% / 4.7% / 7.7% off;
//    the new oracle alone was worse (fewer links): the push fixes rooms at any feps;
//  * the Cornell box with the published floor (now cornell_box_uncut_floor.obj) against the full
//    matrix at its defaults (492 elements, 16 visibility samples): worst |B_hr - B_full| over
//    patches and channels relative to the larger of the patch's brightest channel and the
//    reflectors' mean; HR's seconds / elements / links:
//      feps 0.04   1.9%  1.8 s  492 / 11864        feps 0.005   0.8%  7.4 s  492 / 47692
//      feps 0.02   1.6%  2.5 s  492 / 20778        feps 0.0025  0.3% 10.4 s  492 / 65528
//      feps 0.01   0.8%  2.2-4.5 s 492 / 31310     (aeps total/1000; at feps 0.01, 2.2 s unloaded)
//    With 9 visibility samples for both, feps 0.01: 1.4%. HSA's oracle and push at the old defaults
//    (feps 0.005, aeps total/500): 5.4%, 297 elements, 29924 links, ~2 s. The full matrix itself
//    is up to 2.9% from one with 4x smaller elements (1968), and so is HR at feps 0.0025.
//    Before the partly visible rule bounded point factors, a floor / back-wall pair whose 16
//    samples all hit a block was linked with factor 0 and the box came out 27% dark.
// So kAutoFeps = 0.01 and aeps = total/1000: rooms exact per element, the Cornell box within 1%
// of the full matrix in a few seconds. There is no automatic bfeps: B*F refinement (HSA sec. 4.2)
// is used when --bfeps is given.
#pragma once

#include <optional>

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

class ElementHierarchy;
class SolverContext;

/// The tolerances a hierarchical solve uses after the automatic defaults are applied.
struct HierarchicalTolerances {
  double feps = 0.0;   ///< form-factor tolerance (0 = not used)
  double bfeps = 0.0;  ///< B*F tolerance in radiosity units (0 = not used)
  double aeps = 0.0;   ///< smallest element area (scene units squared), > 0
};

/// Applies the defaults: feps = kAutoFeps when both feps and bfeps are 0; aeps = kAutoAepsFraction
/// times the total area when aeps is 0.
HierarchicalTolerances hierarchical_tolerances(const Scene& scene, const SolveOptions& options);

/// The start both hierarchical solves (plain and clustered) share: records `t` in the report's
/// figures "feps", "bfeps" and "aeps"; when nothing reflects, finishes `ctx` with B = E and no links
/// and returns its summary (the caller returns it as is).
std::optional<SolveSummary> start_hierarchical(SolverContext& ctx, const ElementHierarchy& h,
                                              const HierarchicalTolerances& t, Solution* out);

/// Largest radiosity a closed scene can reach: with factors summing to at most 1 per element,
/// B <= E_max / (1 - rho_max) (the Neumann series of B = E + rho F B); the iterations' divergence test.
double radiosity_bound(const Scene& scene);

/// The end both share, before SolverContext::finish(): a gray scene's channel 0 copied to all three,
/// and the figures "min_element_area" (smallest leaf) and "max_depth".
void end_hierarchical(SolverContext& ctx, ElementHierarchy& h);

/// Solves `scene` by hierarchical radiosity (options.method is ignored) and writes the leaves to
/// `out` (if not null). Summary: links counts directed links (each stored interaction is gathered
/// both ways and counts twice, as the n^2 of the full matrix counts both directions); figures
/// "feps", "bfeps", "aeps", "refine_passes", "link_pairs", "leaf_links" (terms gathered per
/// iteration, see hierarchical_leaf_factors.h), "min_element_area", "max_depth".
SolveSummary solve_hierarchical(const Scene& scene, const SolveOptions& options, Solution* out);

}  // namespace hrad
