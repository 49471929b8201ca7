// Hierarchical radiosity with clustering: Smits, Arvo & Greenberg 1994 ("A clustering algorithm
// for radiosity in complex environments") with Sillion's 1995 oriented cluster transfer.
//
// A binary volume hierarchy of clusters (ClusterTree) sits above the patches' quadtrees. The whole
// scene is linked from one root self-link and refined top-down (breadth-first; each level decided
// in parallel, split in order, so the result is the same at any thread count):
//  * a cluster's self-link becomes the links between its two children and their self-links;
//  * a pair farther apart than 3 times the sum of its bounding radii is linked with the far-field
//    transfer (cluster_transfer.h) when its error, estimated as the factor times the change of the
//    1/r^2 falloff across the two spheres, 2 (r_p + r_q) / r, plus the sampled visibility error,
//    times the source's a-priori radiosity weight (solve_hierarchical()'s), is within feps; this
//    holds for element pairs too, so far element pairs need no exact kernel;
//  * other pairs with a cluster split the side with the larger bounding sphere;
//  * other element pairs go to solve_hierarchical()'s refinement and leaf-exact links
//    (hierarchical_refine.h, hierarchical_leaf_factors.h): near interactions are plain HSA.
// Links are stored grouped by receiver: element-to-element links in 8 bytes (32-bit source, float
// factor), links with a cluster end in 20 bytes (plus the direction), gathered in parallel over
// receivers, each summing its own links in a fixed order. Clusters are oriented (Sillion 1995): a
// cluster shows, towards a direction, the mean radiosity of its surfaces weighted by their
// projected areas (kept per signed axis), and spreads what it receives over its surfaces by their
// projected area towards the source (per signed axis, conserving the link's power); push-pull runs
// through the clusters into the quadtrees.
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
