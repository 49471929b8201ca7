// Hierarchical radiosity: Hanrahan, Salzman & Aupperle 1991, "A rapid hierarchical radiosity
// algorithm" (SIGGRAPH '91; "HSA" below), with clustering above the input polygons (Smits, Arvo &
// Greenberg 1994; oriented clusters after Sillion 1995).
//
// One quadtree per input patch (ElementHierarchy); with clustering, a binary volume hierarchy
// (ClusterTree) above them. Refinement (refine.h) starts from every pair of patches (plain HSA) or
// from the root cluster's self-link (clustered) and asks one oracle (refinement_oracle.h) per
// pair: drop, link, or split the side whose gather errs more, never below the smallest area aeps.
// The links are solved by Jacobi iterations of gather and push-pull (iteration.h) until the
// estimated error is below SolveOptions::tolerance. With --bfeps the links are re-refined with the
// current radiosity after each solve (HSA sec. 4.2) until nothing changes; with feps, only the links
// at elements the solve found far brighter than their a-priori weight (ErrorBoundOracle::observe()).
//
// Two link operators:
//  * Push::kHsa (the default): each link is gathered at the nodes it joins and pushed down
//    (hsa_links.h, push_pull.h): one term per directed link per iteration, O(links + nodes). A leaf
//    receives its ancestors' average factors; how far that strays from its own is what the oracle
//    bounds (feps), so in a closed room each patch balances exactly and each element to about feps.
//  * Push::kLeaf: element links resolved to the leaves on both sides with each leaf's own factor
//    (leaf_links.h): exact per element in closed rooms, at one term per (leaf, link on its path).
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

/// True when the hierarchical solve clusters (clustering on, or auto with at least
/// kAutoClusteringPatches patches).
bool uses_clustering(const Scene& scene, const SolveOptions& options);

/// Solves `scene` by hierarchical radiosity (options.method is ignored) and writes the leaves to
/// `out` (if not null). Summary: links counts directed links (each stored interaction is gathered
/// both ways and counts twice, as the n^2 of the full matrix counts both directions); work as
/// counted; figures "feps", "bfeps", "aeps", "refine_passes", "link_pairs", "partial_links",
/// "cluster_link_pairs", "clusters", "min_element_area", "max_depth". `kept`, when given, receives
/// the hierarchy, the cluster tree and the links (solved_hierarchy.h).
SolveSummary solve_hierarchical(const Scene& scene, const SolveOptions& options, Solution* out,
                                SolvedHierarchy* kept = nullptr);

}  // namespace hrad
