// The refinement oracle of hierarchical radiosity: for a pair of nodes (elements or clusters), drop
// it, link it, or split one side (Hanrahan, Salzman & Aupperle 1991, "Refine"; Smits, Arvo &
// Greenberg 1994 for clusters). One interface for every rule; the plain and the clustered solves
// ask the same oracle (a plain solve starts from the pairs of input patches, a clustered one from
// the root cluster's self-link).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "hrad/core/bright_emitters.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/cluster_transfer.h"
#include "hrad/solvers/cluster_tree.h"
#include "hrad/solvers/form_factor_evaluator.h"

namespace hrad {

enum class Decision : std::uint8_t {
  kDrop,    ///< no exchange (coplanar, facing away, hidden)
  kLink,    ///< store the link with the factors in the candidate
  kSplitP,  ///< replace by (child of p, q) for each child of p
  kSplitQ,  ///< replace by (p, child of q)
  kSelf,    ///< a cluster's self-link: its children's self-links and the links between them
  /// No link: the pair is partly visible but every sampled point pair was blocked. A sampled
  /// estimate whose count followed the ends' weights: decided again when an end turns out brighter
  /// than weighed (RefineResult::unseen).
  kUnseen,
};

/// A pair of nodes under examination. Links are two-way: p gathers from q with f_pq = F(p -> q)
/// and q from p with f_qp = F(q -> p).
struct Candidate {
  NodeRef p = kNoNode;
  NodeRef q = kNoNode;
  /// From the parent pair: the shaft of a sub-pair lies in its parent's, so a fully visible parent
  /// has fully visible children, and a partly visible parent's occluders are the only candidates
  /// for its children (`occluders`; null = the whole scene).
  bool known_visible = false;
  std::shared_ptr<const std::vector<int>> occluders = nullptr;
  /// Split p whatever the pair's error (a re-refinement of shadowed receivers, refine.h).
  bool split_p = false;

  // Filled by RefinementOracle::decide().
  Decision decision = Decision::kDrop;
  /// What the pair's own classification found: children inherit it (when split).
  bool visible = false;
  std::shared_ptr<const std::vector<int>> found_occluders = nullptr;
  double f_pq = 0.0;
  double f_qp = 0.0;
  bool partial = false;  ///< linked with a sampled visible fraction (the shaft test found occluders; a cluster link)
  /// Between elements: the linked visible fraction (f_pq = unoccluded F(p -> q) times it; 1 unless partial).
  double fraction = 1.0;
  /// A link with a cluster end: the patches of a cluster p (q) that face the other end, with the
  /// part of the other end each sees and its sampled factor to it (FormFactorEvaluator::
  /// shaded_surfaces(); null when none). A patch gets through the link in proportion to its factor
  /// to the other end's sphere times the part it sees, and sends by its own factor (hsa_links.h):
  /// a patch that sees nothing of the other end takes no part.
  std::shared_ptr<const ShadedPatches> hidden_p = nullptr, hidden_q = nullptr;
  /// A partly visible link's error from giving each side the link's visible fraction, as the
  /// weighted test counts it (1 = the tolerance): what its receiver gathers errs by this much where
  /// the visibility differs from the fraction.
  float shadow_p = 0.0f, shadow_q = 0.0f;
  /// The link's factor as the weighted test counts it (f_pq w(q) / feps, ...): what each side
  /// gathers through it, in the same units.
  float share_p = 0.0f, share_q = 0.0f;
  /// Between elements: the factor's shape over each side, F(x -> q) V(x, q) at its points
  /// (link_operator.h PointValues) moved to the link's mean factor (with constant leaves, a partly
  /// visible link's visible point factors scaled up to it where its mean is the larger:
  /// refinement_oracle.cpp shape_of()), which the HSA push carries down to the leaves.
  bool shaped = false;
  std::array<float, 9> shape_p{}, shape_q{};
  /// Between elements: what p sends through the link is sum_i source_p[i] m_i over the moments of
  /// its radiosity (link_operator.h): shape_p over the exchange. The same for q.
  std::array<float, 9> source_p{}, source_q{};
};

class RefinementOracle {
 public:
  virtual ~RefinementOracle() = default;
  /// Examines `c` and sets its decision (and, for a link, its factors). Reads the hierarchy only:
  /// safe to call for many candidates at once; deterministic.
  virtual void decide(Candidate& c) const = 0;
  /// Whether `r` can be split (an element above the smallest area, or a cluster).
  virtual bool can_split(NodeRef r) const = 0;
};

/// Tolerances after the automatic defaults (hierarchical_tolerances()).
struct OracleTolerances {
  double feps = 0.0;   ///< 0 = no form-factor test
  double bfeps = 0.0;  ///< 0 = no B*F test (radiosity units)
  double aeps = 0.0;   ///< an element splits only while its children's area stays >= aeps
  /// True: a link's error is measured from a linear field through its receiver's corners (the HSA
  /// push carries each link's field, push_pull.h); false: from its constant mean factor (as HSA
  /// 1991 pushes; the leaf push, which resolves each link per leaf, keeps links that fine).
  bool fields = true;
  /// True (with `fields`): the leaves hold linear fields (--basis linear), which keep the part of a
  /// link's factor field that a linear (bilinear) field over the receiver represents, so a link's
  /// error is what the least-squares linear fit of its visible point factors leaves at the points
  /// (Gortler, Schroeder, Cohen & Hanrahan 1993, "Wavelet radiosity": a link is kept where the
  /// kernel is well represented by the basis at that level; Zatz 1993's Galerkin bases). False: the
  /// error of the linear field through the receiver's corners moved to the link's mean, which the
  /// constant basis's refinement reads.
  bool linear_leaves = false;
  /// Quadtree levels below aeps to which an element may still split as a source (with `fields`).
  /// Where a receiver's kernel peaks over part of a source (a contact, the inside of a lamp's
  /// housing 2 cm from its emitter), what the receiver gathers is that part's radiosity, which a
  /// leaf at aeps averages with the rest: the inner top of RenderPark's office2 lamp housing comes
  /// out 27% too bright at the defaults so. Such a source splits on while its area stays >=
  /// aeps / 4^source_levels and the test below finds the receiver's error from its varying
  /// reflected radiosity above the tolerance. 0: aeps bounds every split.
  int source_levels = 0;
  /// Per patch, whether its elements may split below aeps as sources (empty: all may).
  std::vector<char> source_patches;
  /// The standard deviation over sample streams the power balance should have (0: the default
  /// sampling, whose spread is about 1e-3 in cluttered closed rooms). Element links then take point
  /// pairs in proportion to their share of the power, and each cluster-link end casts more rays
  /// (ErrorBoundOracle::decide_elements(), decide_with_cluster()).
  double power_noise = 0.0;
};

/// Pairs of clusters (or a cluster and an element) farther apart than this many times the sum of
/// their bounding radii take the first-order change of 1/r^2 across them as their link's error;
/// nearer pairs with disjoint spheres its whole range and their ends' share noise (ErrorBoundOracle).
inline constexpr double kClusterSeparation = 3.0;
static_assert(kClusterSeparation > 1.0, "a far pair's spheres must be disjoint");

/// The error-bounding oracle. An element pair is linked when the error its link makes, as a
/// receiver gathers it, is within the tolerance on both sides: at the corner, edge-midpoint and
/// centre points x_i of p (simpson_rule.h) the factor F(x_i -> q) times x_i's visible fraction of q
/// strays from the link's field over p (a linear field through p's corners with the link's mean;
/// with linear leaves the least-squares linear field of the points, which is what a linear leaf
/// keeps; or the mean itself: OracleTolerances) by at most feps / w(q), w(q) the source's a-priori
/// radiosity weight (hierarchical_tolerances() and source_weights()); the same for q. This is the
/// error at receiver points that HSA 1991 sec. 4 asks to bound, in place of their F > feps test,
/// and it sees both the falloff and shadows across the receiver (Lischinski, Smits & Greenberg
/// 1994; Holzschuch & Sillion 1998). With the HSA push the source side counts too: p weighs q's
/// radiosity by the link's field over q, so the field's error relative to its mean over q, times
/// q's weight, bounds what p's gather errs by where q's radiosity varies; it splits q. With bfeps,
/// the source's current radiosity replaces its weight (HSA sec. 4.2). The link's unoccluded factor
/// comes from the same points (the two sides' quadratures, reciprocal by construction) or, where
/// they disagree (near field) or the link is forced at the smallest area, from the analytic kernel.
/// Visibility: each pair is classified with its parent's occluder list; a partly visible pair's
/// points are classified from their own cones, and rays sample only the points that see part of
/// the source.
///
/// Pairs with a cluster: a pair whose bounding spheres are disjoint is linked by a sampled factor
/// (FormFactorEvaluator::sampled(), visibility by rays) when the factor's change across the two
/// spheres plus its standard error passes the same weighted test; otherwise the larger side is
/// split. Beyond kClusterSeparation times the radii the change is 2 (r_p + r_q) / r of the factor
/// (first order); nearer, the whole range of 1/r^2 over the spheres, ((r + r_p + r_q) / (r - r_p -
/// r_q))^2 - 1, plus the noise of each cluster end's shares (near_share_noise()). Such near links
/// stand for the element pairs below them: on the generated warehouse the element link pairs per
/// patch then stay at 42-44 from 1k to 16k polygons, where splitting every near pair down to its
/// elements made them grow from 56 to 73.
class ErrorBoundOracle final : public RefinementOracle {
 public:
  /// `tree` may be null (no clusters). `cluster_radiosity` (per cluster) and the hierarchy's
  /// radiosity are read by the B*F test. References are kept.
  ErrorBoundOracle(const ElementHierarchy& hierarchy, const ClusterTree* tree, const ClusterTransfer& geometry,
                   const FormFactorEvaluator& evaluator, const OracleTolerances& tolerances,
                   std::vector<double> patch_weights, int channels, const std::vector<Rgb>* cluster_radiosity);

  void decide(Candidate& c) const override;
  bool can_split(NodeRef r) const override;

  /// After a solve with feps: the elements whose brightest leaf is more than kBrighterThanWeighed
  /// times their weight (in units of B_mean) take that brightness as their weight from now on, and
  /// are returned (per element id, 1 where raised). The a-priori weight takes a reflector's
  /// radiosity as rho B_mean; next to a lamp a reflector is far brighter (a wall a millimetre from
  /// a lamp: ~500 B_mean under it against 0.7), and the links from its coarse elements carry that
  /// bright footprint with a field over the source that cannot follow it. Only the links at raised
  /// elements need deciding again: no other decision reads a changed weight. Nothing is raised with
  /// bfeps alone (its B*F test already reads the radiosity).
  std::vector<char> observe();

 private:
  void decide_elements(Candidate& c) const;
  void decide_with_cluster(Candidate& c) const;
  /// The rays each patch of a cluster link's end casts for its sends (at least kFacingRays).
  int end_rays_per_patch(NodeRef end) const;
  /// A pair nearer than kClusterSeparation: each patch of a cluster end gets its share of the link
  /// by its own end_rays_per_patch() rays (hsa_links.h), whose factor to the other end errs by about
  /// its largest value `largest` (TransferBound) over the root of their number; 0 for an element end
  /// (one share, the link's).
  double near_share_noise(NodeRef end, double largest) const;
  /// Each side's weighted error over its tolerance (pass when both are <= 1): err_p is the error of
  /// what p gathers from q per unit radiosity of q.
  std::pair<double, double> weighted(NodeRef p, NodeRef q, double err_p, double err_q) const;
  double weight(NodeRef r) const;
  /// err_p and err_q in units of the tolerances: with feps, times the other side's `feps_weight`;
  /// with bfeps, times its `bfeps_radiosity`; the larger of the two.
  template <class FepsWeight, class BfepsRadiosity>
  std::pair<double, double> weigh(FepsWeight feps_weight, BfepsRadiosity bfeps_radiosity, NodeRef p, NodeRef q,
                                  double err_p, double err_q) const {
    double wp = 0.0, wq = 0.0;
    if (tol_.feps > 0.0) {
      wp = feps_weight(q) * err_p / tol_.feps;
      wq = feps_weight(p) * err_q / tol_.feps;
    }
    if (tol_.bfeps > 0.0) {
      wp = std::max(wp, bfeps_radiosity(q) * err_p / tol_.bfeps);
      wq = std::max(wq, bfeps_radiosity(p) * err_q / tol_.bfeps);
    }
    return {wp, wq};
  }
  /// What the source side of a link errs by (source_levels > 0): like weighted(), with each side
  /// weighted by how far its radiosity can vary over it: its weight less its emission (uniform over
  /// a patch), or with bfeps its reflected radiosity B - E.
  std::pair<double, double> varied(NodeRef p, NodeRef q, double err_p, double err_q) const;
  /// An element at aeps that may still split as a source (OracleTolerances::source_levels).
  bool can_split_source(NodeRef r) const;
  double brightest(NodeRef r) const;
  Decision split_choice(NodeRef p, NodeRef q, double e_p, double e_q) const;

  const ElementHierarchy& h_;
  const ClusterTree* tree_;
  const ClusterTransfer& geometry_;
  const FormFactorEvaluator& evaluator_;
  OracleTolerances tol_;
  std::vector<double> patch_weight_;
  std::vector<double> patch_emitted_;  ///< per patch: the largest E / B_mean over the channels (source levels only)
  std::vector<double> cluster_weight_;
  int channels_;
  const std::vector<Rgb>* cluster_radiosity_;
  int pair_samples_;
  /// Rays each cluster-link end casts for its sends, shared among its patches: --visibility-samples,
  /// times (kClusterSendNoise / power_noise)^2 with OracleTolerances::power_noise.
  double cluster_end_rays_;
  double total_area_ = 0.0;   ///< the scene's: a link's weighted exchange over it is its share of the power
  Rgb b_mean_ = Rgb::Zero();  ///< mean_radiosity() of the scene
  /// Per element (as numbered when last observed): its weight then; empty before any observe().
  std::vector<double> observed_;
};

/// observe() raises an element's weight when its brightest leaf passes its weight by this factor.
inline constexpr double kBrighterThanWeighed = 8.0;

/// The feps weights: a priori radiosity of each patch relative to the scene's, w = max over
/// channels of (E / B_mean + rho), with B_mean = Ebar / (1 - rhobar) the closed-room radiosity of
/// the area-mean emission and reflectance. What p gathers through a link is B_q times the factor,
/// so B_q / B_mean turns a factor error into a relative radiosity error; B_q is estimated before
/// solving as E_q + rho_q B_mean. In a closed room with uniform E and rho every weight is 1 (plain
/// feps). All 1 when nothing emits. Only `channels` channels count (1 or 3).
std::vector<double> source_weights(const Scene& scene, int channels);

}  // namespace hrad
