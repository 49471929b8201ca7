// Hierarchical radiosity with clustering: Smits, Arvo & Greenberg 1994 ("A clustering algorithm
// for radiosity in complex environments") with Sillion's 1995 oriented cluster transfer.
//
// A binary volume hierarchy of clusters (ClusterTree) sits above the patches' quadtrees. The whole
// scene is linked from one root self-link and refined top-down: a cluster's self-link becomes the
// links between its children (and their self-links); a pair involving a cluster is linked when the
// bound of its factors (cluster_transfer.h) is within feps (or B*F within bfeps), otherwise the
// node with the larger bounding sphere is split (a cluster into its two children, an element 1-to-4
// down to aeps); pairs of elements are refined as in plain HSA (hierarchical.h) with the shared
// FormFactorEvaluator. Gather runs over links stored by receiver (each directed link 8 bytes: a
// 32-bit source and a 32-bit float factor) in parallel over receivers, each summing its links in a
// fixed order, so the result is the same at any thread count. Push-pull goes through the clusters:
// what a cluster gathers is pushed to its children (uniformly per unit area: Sillion's isotropic
// receiver), and a cluster's radiosity is the area-weighted mean of its children (the power average
// it shoots with).
#pragma once

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/solvers/solve.h"

namespace hrad {

/// True when solve() runs the clustered solver for `options` (hierarchical method and clustering
/// on, or auto with at least kAutoClusteringPatches patches).
bool uses_clustering(const Scene& scene, const SolveOptions& options);

/// Solves by clustered hierarchical radiosity. Tolerances and their defaults are those of
/// solve_hierarchical() (hierarchical_tolerances()). Summary: links counts directed links; figures
/// as solve_hierarchical() plus "clusters", "cluster_link_pairs" (link pairs with a cluster at one
/// end), "cluster_estimates", "bytes_per_link" (directed link storage) and "link_bytes".
SolveSummary solve_clustered_hierarchical(const Scene& scene, const SolveOptions& options, Solution* out);

}  // namespace hrad
