#include "hrad/solvers/hierarchical_refine.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/geometry/polygon.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace hrad::detail {
namespace {

double brightest(const ElementNode& node, int channels) {
  return channels == 1 ? node.radiosity[0] : node.radiosity.maxCoeff();
}

bool can_split(const ElementNode& node, double aeps) { return node.area * 0.25 >= aeps; }

enum class Decision { kDrop, kLink, kSplitP, kSplitQ };

Decision decide(const ElementHierarchy& h, const RefineCandidate& c, const RefineTolerances& tol, int channels) {
  if (!c.split_unevaluated) {
    const FormFactorEstimate& e = c.estimate;
    if (e.facing_away) return Decision::kDrop;
    // Fully hidden (visibility classified 0 exactly) or coplanar: the pair exchanges nothing.
    if (e.value <= 0.0 && e.reverse <= 0.0 && e.error <= 0.0) return Decision::kDrop;
    if (!pair_needs_refinement(h, c, tol, channels)) return Decision::kLink;
  }
  const ElementNode& p = h.node(c.p);
  const ElementNode& q = h.node(c.q);
  // Split the side whose gather errs more, as the test weighs it: p's error (the factor's variation
  // over p) times q's weight, against q's times p's. Only splitting p reduces p's error; splitting
  // q instead makes each child's share small enough to pass while the children's errors add up on
  // p (unweighted, the Cornell box's light was split into 213 mm^2 pieces, each linked to whole
  // floor elements across the tall block's shadow: 4.6% too bright behind it). On a tie (the
  // visibility error decided), the larger one, as HSA 1991 Refine does.
  const auto [error_p, error_q] = weighted_errors(h, c, tol, channels);
  const bool q_first = error_q != error_p ? error_q > error_p : q.area > p.area;
  if (q_first) {
    if (can_split(q, tol.aeps)) return Decision::kSplitQ;
    if (can_split(p, tol.aeps)) return Decision::kSplitP;
  } else {
    if (can_split(p, tol.aeps)) return Decision::kSplitP;
    if (can_split(q, tol.aeps)) return Decision::kSplitQ;
  }
  return Decision::kLink;  // both at the smallest area: link anyway (HSA)
}

}  // namespace

PointFactorSpread factor_variation(std::span<const Vec3> receiver, std::span<const Vec3> source) {
  const Vec3 n = newell_normal(receiver).normalized();
  const std::size_t k = receiver.size();
  PointFactorSpread spread;
  auto sample = [&](const Vec3& x) {
    const double f = point_to_polygon(x, n, source);
    spread.largest = std::max(spread.largest, f);
    spread.smallest = std::min(spread.smallest, f);
  };
  sample(polygon_centroid(receiver));
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& a = receiver[i];
    const Vec3& b = receiver[i + 1 == k ? 0 : i + 1];
    sample(a);
    sample(0.5 * (a + b));
  }
  return spread;
}

std::size_t directed_link_count(std::span<const LinkPair> pairs) {
  std::size_t count = 0;
  for (const LinkPair& pair : pairs) count += (pair.estimate.value > 0.0) + (pair.estimate.reverse > 0.0);
  return count;
}

void evaluate_candidate(const ElementHierarchy& h, const FormFactorEvaluator& evaluator, RefineCandidate& c,
                        const RefineTolerances* tol) {
  const ElementNode& p = h.node(c.p);
  const ElementNode& q = h.node(c.q);
  c.evaluated = true;
  c.split_unevaluated = false;
  c.estimate = FormFactorEstimate{};
  c.variation_p = c.variation_q = 0.0;
  const PointFactorSpread s_p = factor_variation(p.polygon(), q.polygon());
  const PointFactorSpread s_q = factor_variation(q.polygon(), p.polygon());
  if (tol != nullptr && tol->feps > 0.0 && tol->bfeps <= 0.0 && (can_split(p, tol->aeps) || can_split(q, tol->aeps))) {
    // Whatever the average, some sample deviates from it by at least half the samples' spread, so
    // the full test below would refine too (unless the pair is hidden or faces away, whose
    // children are then dropped one level lower): split without the kernel and visibility calls,
    // which cost ~10x the point factors. Not with bfeps, whose passes re-test the stored pairs.
    const double half_p = 0.5 * (s_p.largest - s_p.smallest);
    const double half_q = 0.5 * (s_q.largest - s_q.smallest);
    if (std::max(tol->weight(q.patch) * half_p, tol->weight(p.patch) * half_q) > tol->feps) {
      c.variation_p = half_p;
      c.variation_q = half_q;
      c.split_unevaluated = true;
      return;
    }
  }
  c.estimate = evaluator.estimate(p.polygon(), p.patch, q.polygon(), q.patch);
  const FormFactorEstimate& e = c.estimate;
  // Facing away, hidden or coplanar: dropped, nothing to bound. A partly visible pair whose samples
  // all hit an occluder has value 0 but an error, and is bounded below.
  if (e.facing_away || (e.value <= 0.0 && e.reverse <= 0.0 && e.error <= 0.0)) return;
  const double f_pq = e.unoccluded;
  const double f_qp = e.unoccluded * p.area / q.area;  // reciprocity
  const double dev_p = std::max(s_p.largest - f_pq, f_pq - s_p.smallest);
  const double dev_q = std::max(s_q.largest - f_qp, f_qp - s_q.smallest);
  if (!e.partial) {
    c.variation_p = dev_p;
    c.variation_q = dev_q;
  } else {
    // Partly visible: a shadow boundary may cross the receiver, and every point of it gets the
    // pair's mean visible fraction, so a point's error can be as large as its unoccluded factor.
    // By the classification, not the sampled fraction: a pair whose samples all passed is still
    // partly hidden. Accepting it as visible lit the floor behind the Cornell box's tall block too
    // brightly once the light's elements got small enough for every sample to miss the block: at
    // aeps = total/10000, 11.3% off an 8k-element full matrix before this rule, 4.6% after it (and
    // 1.7% with decide()'s weighted split choice).
    c.variation_p = std::max(e.visibility * dev_p, s_p.largest);
    c.variation_q = std::max(e.visibility * dev_q, s_q.largest);
  }
}

std::pair<double, double> weighted_errors(const ElementHierarchy& h, const RefineCandidate& c,
                                          const RefineTolerances& tol, int channels) {
  const FormFactorEstimate& e = c.estimate;
  const ElementNode& p = h.node(c.p);
  const ElementNode& q = h.node(c.q);
  // What p gathers is F(p->q) B_q: its error is the factor's variation over p (and, by reciprocity,
  // the variation over q times q's variation of B) plus the visibility error, whose bound for
  // F(q->p) follows by reciprocity: A_p F(p->q) = A_q F(q->p).
  const double err_pq = e.error;
  const double err_qp = e.error * p.area / q.area;
  const double error_p = c.variation_p + err_pq;  // of what p gathers from q, per unit B_q
  const double error_q = c.variation_q + err_qp;
  // Each side's error relative to its tolerance: feps with the source's weight, or (HSA 1991 sec.
  // 4.2) bfeps with the source's current radiosity; the larger of the two tests.
  double wp = 0.0, wq = 0.0;
  if (tol.feps > 0.0) {
    wp = tol.weight(q.patch) * error_p / tol.feps;
    wq = tol.weight(p.patch) * error_q / tol.feps;
  }
  if (tol.bfeps > 0.0) {
    wp = std::max(wp, brightest(q, channels) * error_p / tol.bfeps);
    wq = std::max(wq, brightest(p, channels) * error_q / tol.bfeps);
  }
  return {wp, wq};
}

bool pair_needs_refinement(const ElementHierarchy& h, const RefineCandidate& c, const RefineTolerances& tol,
                           int channels) {
  const auto [error_p, error_q] = weighted_errors(h, c, tol, channels);
  return std::max(error_p, error_q) > 1.0;
}

std::vector<double> source_weights(const Scene& scene, int channels) {
  Rgb emitted = Rgb::Zero(), reflectance = Rgb::Zero();
  double area = 0.0;
  for (const Patch& p : scene.patches) {
    const Material& m = scene.material_of(p);
    emitted += p.area * m.emission;
    reflectance += p.area * m.reflectance;
    area += p.area;
  }
  std::vector<double> weights(scene.patches.size(), 1.0);
  if (area <= 0.0) return weights;
  // Closed-room radiosity of the mean emission and reflectance (rhobar capped: a lossless scene
  // with light in it has no finite mean, and the weights only need to rank sources).
  const Rgb rho_bar = (reflectance / area).min(0.999);
  const Rgb b_mean = (emitted / area) / (1.0 - rho_bar);
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Material& m = scene.material_of(scene.patches[i]);
    double w = 0.0;
    bool any = false;
    for (int c = 0; c < channels; ++c) {
      if (!(b_mean[c] > 0.0)) continue;
      w = std::max(w, m.emission[c] / b_mean[c] + m.reflectance[c]);
      any = true;
    }
    if (any) weights[i] = w;
  }
  return weights;
}

RefineResult refine_pairs(ElementHierarchy& h, const FormFactorEvaluator& evaluator, std::vector<RefineCandidate> work,
                          const RefineTolerances& tol, int channels) {
  RefineResult result;
  const std::size_t nodes_before = h.size();
  std::vector<RefineCandidate> next;
  while (!work.empty()) {
    // Estimates of one level in parallel: no node is split meanwhile, so the polygons are stable.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, work.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          RefineCandidate& c = work[i];
                          if (!c.evaluated) evaluate_candidate(h, evaluator, c, &tol);
                        }
                      });
    next.clear();
    for (const RefineCandidate& c : work) {
      switch (decide(h, c, tol, channels)) {
        case Decision::kDrop:
          ++result.dropped;
          break;
        case Decision::kLink:
          result.links.push_back(c);
          break;
        case Decision::kSplitP: {
          ++result.splits;
          const NodeId child = h.split(c.p);
          for (NodeId k = 0; k < 4; ++k) next.push_back(candidate(child + k, c.q));
          break;
        }
        case Decision::kSplitQ: {
          ++result.splits;
          const NodeId child = h.split(c.q);
          for (NodeId k = 0; k < 4; ++k) next.push_back(candidate(c.p, child + k));
          break;
        }
      }
    }
    std::swap(work, next);
  }
  result.new_nodes = h.size() - nodes_before;
  return result;
}

}  // namespace hrad::detail
