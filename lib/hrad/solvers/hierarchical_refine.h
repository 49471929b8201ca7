// Refinement of element pairs into links for hierarchical radiosity (HSA 1991, "Refine").
//
// The oracle bounds the error a link makes, not the size of its factor. A link gives every point
// of p the area-averaged factor F(p -> q) (and every point of q the average F(q -> p)); its error
// is how far the point-to-element factor F(x -> q) of points x of p strays from that average
// (HSA 1991 sec. 4 on the error of constant links; Lischinski, Smits & Greenberg 1994, "Bounds and
// error estimates for radiosity", sec. 3; Holzschuch & Sillion 1998, "An exhaustive error-bounding
// algorithm for hierarchical radiosity", sec. 3). The same variation is the error of gathering q's
// mean radiosity when B varies over q: by reciprocity the kernel p sees on q is proportional to
// F(y -> p), y on q. We estimate it at the vertices, edge midpoints and centroid of each element
// (the points its children's corners will be) with Lambert's point-to-polygon formula, which costs
// about a tenth of one analytic polygon-to-polygon factor per point.
#pragma once

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/form_factor_evaluator.h"

namespace hrad::detail {

/// A pair of elements under consideration, with its estimate once evaluated (re-refinement
/// passes reuse the estimate of an existing link instead of calling the kernel again).
struct RefineCandidate {
  NodeId p = kNoNode;
  NodeId q = kNoNode;
  bool evaluated = false;
  FormFactorEstimate estimate;  ///< receiver p, source q
  /// Error bound of the factor p's points get, F(p -> q): the largest |F(x -> q) - F(p -> q)| over
  /// p's sample points x times the visible fraction; for a partly visible pair at least the
  /// largest F(x -> q) (a shadow boundary may cross p).
  double variation_p = 0.0;
  /// The same for q's points and F(q -> p).
  double variation_q = 0.0;
  /// Split on its point factors alone (see evaluate_candidate()): estimate not computed.
  bool split_unevaluated = false;
};

/// A fresh candidate for the pair (p, q).
inline RefineCandidate candidate(NodeId p, NodeId q) {
  RefineCandidate c;
  c.p = p;
  c.q = q;
  return c;
}

/// A stored interaction between p and q: p gathers from q with estimate.value = F(p -> q) and q
/// gathers from p with estimate.reverse = F(q -> p).
using LinkPair = RefineCandidate;

/// Directed links: both directions of every stored interaction that carries a factor.
std::size_t directed_link_count(std::span<const LinkPair> pairs);

struct RefineTolerances {
  double feps = 0.0;   ///< 0 = no form-factor test
  double bfeps = 0.0;  ///< 0 = no B*F test
  double aeps = 0.0;   ///< a node is split only when its children's area stays >= aeps
  /// Per patch: the feps test compares a link's factor error times the weight of its source's
  /// patch (see source_weights()); empty = weight 1 everywhere.
  std::vector<double> source_weight;
  double weight(int patch) const { return source_weight.empty() ? 1.0 : source_weight[static_cast<std::size_t>(patch)]; }
};

/// The weights of the feps test: a priori radiosity of each patch relative to the scene's,
/// w = max over channels of (E / B_mean + rho), with B_mean = Ebar / (1 - rhobar) the closed-room
/// radiosity of the area-mean emission and reflectance. What p gathers through a link is B_q times
/// the factor, so B_q / B_mean turns a factor error into a relative radiosity error; B_q is estimated
/// before solving as E_q + rho_q B_mean. In a closed room with uniform E and rho every weight is 1
/// (plain feps); in the Cornell box the light's is ~40 and the white walls' 0.74. All 1 when
/// nothing emits. Only the channels `channels` counts (1 or 3).
std::vector<double> source_weights(const Scene& scene, int channels);

struct RefineResult {
  std::vector<LinkPair> links;
  std::size_t splits = 0;      ///< split decisions taken (new or existing children)
  std::size_t new_nodes = 0;   ///< nodes the hierarchy grew by
  std::size_t dropped = 0;     ///< pairs facing away, hidden or coplanar: no link
};

/// Refines `work` breadth-first: all unevaluated candidates of one level are estimated in
/// parallel (each estimate is deterministic), then decided sequentially in order (splits happen
/// only there), so the result does not depend on the thread count. `channels` selects which
/// radiosity channels the B*F test looks at (1 or 3).
RefineResult refine_pairs(ElementHierarchy& hierarchy, const FormFactorEvaluator& evaluator,
                          std::vector<RefineCandidate> work, const RefineTolerances& tolerances, int channels);

/// Point-to-polygon factors F(x -> source) over the sample points x of a receiver (its vertices,
/// edge midpoints and centroid; point_to_polygon() with the receiver's normal; points in the
/// source's plane, e.g. on a shared edge, count as 0, which only makes the spread larger). The
/// largest deviation from an average a is max(largest - a, a - smallest).
struct PointFactorSpread {
  double largest = 0.0;
  double smallest = 1e300;
};
PointFactorSpread factor_variation(std::span<const Vec3> receiver, std::span<const Vec3> source);

/// Fills c.estimate, c.variation_p and c.variation_q (c.evaluated = true). With `tolerances` (feps
/// only, and one of the pair splittable), a pair whose point factors alone prove it needs refining
/// is marked split_unevaluated, without a kernel or visibility call.
void evaluate_candidate(const ElementHierarchy& hierarchy, const FormFactorEvaluator& evaluator, RefineCandidate& c,
                        const RefineTolerances* tolerances = nullptr);

/// Each side's gather error relative to its tolerance: p's (the factor's variation over p plus the
/// visibility error) times q's weight over feps, or times q's radiosity over bfeps (the larger), and
/// the same for q. The pair passes when both are <= 1.
std::pair<double, double> weighted_errors(const ElementHierarchy& hierarchy, const RefineCandidate& pair,
                                          const RefineTolerances& tolerances, int channels);

/// True when the pair must be refined further under `tolerances`: the factors' variation (see the
/// file comment) or their visibility error exceeds feps, or either times the source's current
/// radiosity exceeds bfeps (HSA 1991 sec. 4.2's B*F test, applied to the error).
bool pair_needs_refinement(const ElementHierarchy& hierarchy, const RefineCandidate& pair,
                           const RefineTolerances& tolerances, int channels);

}  // namespace hrad::detail
