// A hierarchical solve's hierarchy and links through its solution file (io/solution_ply.h), so that
// `hrad render --final-gather` and `hrad probe` gather through the links (link_gather.h) as a
// gather in the solve's own process does, at the cost of the links on a point's path rather than
// every patch.
//
// What is stored is what LinkGather reads: the splits (the hierarchy is rebuilt from the scene by
// the same split rule, ElementHierarchy::split, in the order they were made), the cluster tree's
// shape (rebuilt from the scene by ClusterTree and checked against it), and per link its ends, its
// partial flag and the patches of a cluster end that see nothing of the other. The leaves'
// radiosities are the solution's faces' and an interior element's the area mean of its leaves
// (pulled up). The factors and the solver's per-link moments are not stored: a restored
// SolvedHierarchy gathers, it does not iterate.
#pragma once

#include <string>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/io/solution_ply.h"
#include "hrad/solvers/solved_hierarchy.h"

namespace hrad {

/// What `solved` (a hierarchical solve's, with its hierarchy) stores in a solution file.
SolutionLinks stored_links(const SolvedHierarchy& solved);

/// The hierarchy, cluster tree and links of `links` (read from `path` with `solution`), rebuilt on
/// `scene`, which must outlive the result. hrad::Error naming `path` and the element and record when
/// they do not fit the scene or the solution: a split the rule does not make at that point, leaves
/// that are not the solution's faces (count, patch or area), a cluster tree of another shape, a
/// listed patch the scene does not have.
SolvedHierarchy restored_links(const Scene& scene, const Solution& solution, const SolutionLinks& links,
                               const std::string& path);

}  // namespace hrad
