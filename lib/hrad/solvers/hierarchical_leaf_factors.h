// Links gathered by the leaves: HSA's push with each leaf's own factor.
//
// HSA 1991 gather at the link's receiver, an interior node a, and push the gathered irradiance
// F(a -> q) B_q down to every leaf below a unchanged. A leaf thus receives its ancestors' average
// factors, so the factors one leaf gathers through (its own links and its ancestors') do not sum
// to its true total: in a closed room they sum to 1 per patch (the links tile patch x room) but
// from 0.8 to 1.24 per element, which puts corner elements 5% off at rho = 0.9 and makes Jacobi
// diverge at rho = 0.99 (rho times the largest eigenvalue passes 1).
//
// Here the push keeps the link (its source q, the visible fraction, the hierarchy of q that
// provides B_q) but weights it per leaf L with L's own unoccluded factor F(L -> q), from a
// product Gauss rule on L (2 x 2 on a quad, 3 points on a triangle) and Lambert's point-to-polygon
// formula at each point: the receiver side is resolved to the leaves as the full matrix resolves
// it, and the source side stays hierarchical. Each point's factors to sources tiling a closed room
// sum to 1 exactly (Lambert's formula is exact; the sources a leaf reaches through its ancestors'
// links and its own tile the room), so the rows sum to 1 up to how well the rule integrates F over
// L for the sources L reaches through its ancestors; the refinement keeps those far from L (their
// factors vary little over the ancestor), where the rule is accurate. Links whose receiver is a
// leaf keep their exact analytic factor. Cost: one term per (leaf, link of an ancestor), computed
// once per refinement in parallel and gathered each iteration.
#pragma once

#include <span>
#include <vector>

#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/hierarchical_refine.h"
#include "hrad/solvers/solver_context.h"

namespace hrad::detail {

/// F(element -> source) averaged over `element` with the Gauss rule above (unoccluded; the
/// element's normal from its vertex order).
double leaf_form_factor(std::span<const Vec3> element, std::span<const Vec3> source);

/// The links of `pairs`, both directions, with every receiver a leaf: a link to a leaf keeps its
/// factor; a link to an interior node a becomes one link per leaf L below a with factor
/// visibility * leaf_form_factor(L, q). Deterministic order (pair order, then leaves_below()).
std::vector<Link> leaf_links(const ElementHierarchy& hierarchy, std::span<const LinkPair> pairs);

}  // namespace hrad::detail
