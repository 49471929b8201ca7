#include "hrad/solvers/hierarchical_refine.h"

#include <algorithm>
#include <utility>

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
  const FormFactorEstimate& e = c.estimate;
  if (e.facing_away) return Decision::kDrop;
  // Fully hidden (visibility classified 0 exactly) or coplanar: the pair exchanges nothing.
  if (e.value <= 0.0 && e.reverse <= 0.0 && e.error <= 0.0) return Decision::kDrop;
  if (!pair_needs_refinement(h, c, tol, channels)) return Decision::kLink;
  const ElementNode& p = h.node(c.p);
  const ElementNode& q = h.node(c.q);
  // HSA 1991 Refine splits q when F(p->q) > F(q->p), i.e. (reciprocity) the larger element;
  // areas decide the same without relying on a factor that visibility may have zeroed.
  const bool q_first = q.area > p.area;
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

bool pair_needs_refinement(const ElementHierarchy& h, const RefineCandidate& c, const RefineTolerances& tol,
                           int channels) {
  const FormFactorEstimate& e = c.estimate;
  const ElementNode& p = h.node(c.p);
  const ElementNode& q = h.node(c.q);
  const double f_pq = e.value;
  const double f_qp = e.reverse;
  // The visibility error of F(q->p) by reciprocity: A_p F(p->q) = A_q F(q->p).
  const double err_pq = e.error;
  const double err_qp = e.error * p.area / q.area;
  if (tol.feps > 0.0) {
    if (std::max({f_pq, f_qp, err_pq, err_qp}) > tol.feps) return true;
  }
  if (tol.bfeps > 0.0) {
    // HSA 1991 sec. 4.2: what p gathers from q is B_q F(p->q), and the other way round.
    const double b_p = brightest(p, channels);
    const double b_q = brightest(q, channels);
    if (std::max({b_q * f_pq, b_p * f_qp, b_q * err_pq, b_p * err_qp}) > tol.bfeps) return true;
  }
  return false;
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
                          if (c.evaluated) continue;
                          const ElementNode& p = h.node(c.p);
                          const ElementNode& q = h.node(c.q);
                          c.estimate = evaluator.estimate(p.polygon(), p.patch, q.polygon(), q.patch);
                          c.evaluated = true;
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
          for (NodeId k = 0; k < 4; ++k) next.push_back({child + k, c.q, false, {}});
          break;
        }
        case Decision::kSplitQ: {
          ++result.splits;
          const NodeId child = h.split(c.q);
          for (NodeId k = 0; k < 4; ++k) next.push_back({c.p, child + k, false, {}});
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
