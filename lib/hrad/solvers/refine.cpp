#include "hrad/solvers/refine.h"

#include <utility>

#include "hrad/core/progress.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace hrad {
namespace {

// The pair (p', q') below a decided candidate, inheriting what the candidate's classification found.
Candidate child_of(const Candidate& parent, NodeRef p, NodeRef q) {
  Candidate c;
  c.p = p;
  c.q = q;
  c.known_visible = parent.visible;
  c.occluders = parent.visible ? nullptr : (parent.found_occluders ? parent.found_occluders : parent.occluders);
  return c;
}

}  // namespace

namespace {

// Refines `work` breadth-first until every pair is linked or dropped (see refine()).
void refine_levels(ElementHierarchy& h, const ClusterTree* tree, const RefinementOracle& oracle,
                   std::vector<Candidate> work, const std::function<void(std::string_view)>& progress,
                   double progress_interval, RefineResult& result) {
  std::vector<Candidate> next;
  int level = 0;
  while (!work.empty()) {
    // A level of a large scene takes minutes: its pairs decided so far, with an estimate.
    ProgressReporter decided(fmt::format("refine: level {}", level + 1), work.size(), "pairs", progress,
                             progress_interval);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, work.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t i = range.begin(); i != range.end(); ++i) oracle.decide(work[i]);
                        decided.advance(range.size());
                      });
    result.candidates += work.size();
    next.clear();
    for (Candidate& c : work) {
      switch (c.decision) {
        case Decision::kDrop:
          break;
        case Decision::kUnseen:
          result.unseen.push_back({c.p, c.q, c.shadow_p, c.shadow_q, c.share_p, c.share_q});
          break;
        case Decision::kLink:
          result.links.push_back({c.p, c.q, c.f_pq, c.f_qp, c.partial, c.fraction, c.hidden_p, c.hidden_q, c.shadow_p,
                                  c.shadow_q, c.share_p, c.share_q, c.shaped, c.shape_p, c.shape_q, c.source_p,
                                  c.source_q});
          break;
        case Decision::kSelf: {
          const Cluster& k = tree->cluster(cluster_index(c.p));
          next.push_back(child_of(c, k.children[0], k.children[0]));
          next.push_back(child_of(c, k.children[1], k.children[1]));
          next.push_back(child_of(c, k.children[0], k.children[1]));
          break;
        }
        case Decision::kSplitP:
        case Decision::kSplitQ: {
          ++result.splits;
          const bool split_p = c.decision == Decision::kSplitP;
          const NodeRef side = split_p ? c.p : c.q;
          auto add = [&](NodeRef child) {
            next.push_back(split_p ? child_of(c, child, c.q) : child_of(c, c.p, child));
          };
          if (is_cluster(side)) {
            const Cluster& k = tree->cluster(cluster_index(side));
            add(k.children[0]);
            add(k.children[1]);
          } else {
            const NodeId first = h.split(side);
            for (NodeId k = 0; k < 4; ++k) add(first + k);
          }
          break;
        }
      }
    }
    ++level;
    // Levels too short to show progress stay quiet.
    if (progress && decided.lines() > 0)
      progress(fmt::format("refine: level {}: {} pairs examined, {} links, {} elements, {} pairs next", level,
                           work.size(), result.links.size(), h.size(), next.size()));
    std::swap(work, next);
  }
}

// The partial links to refine again: those at an element receiver above a leaf whose summed
// shadow error passes 1, with their receiver to be split (as (receiver, source) candidates). The
// pairs decided kUnseen (`unseen`) count and are refined again alike: they are partly visible
// pairs whose linked samples all happened to be blocked, and what a pair's own samples drew must
// not decide whether it is sampled again. Refining only the pairs drawn bright replaced their draws
// by their parts' unbiased ones while the pairs drawn dark kept 0: a loss of what the latter see
// (rooms of 1 m tiles with floating blocks lost 2.9e-3 of their power at the default 64 samples
// and 2.8% at 16).
std::vector<Candidate> shadowed(const ElementHierarchy& h, const RefinementOracle& oracle, std::vector<Link>& links,
                                std::vector<UnseenPair>& unseen) {
  std::vector<double> own(h.size(), 0.0), gathers(h.size(), 0.0);
  const auto add = [&](const auto& list) {
    for (const auto& l : list) {
      if (!is_cluster(l.p))
        own[static_cast<std::size_t>(l.p)] += l.shadow_p, gathers[static_cast<std::size_t>(l.p)] += l.share_p;
      if (!is_cluster(l.q))
        own[static_cast<std::size_t>(l.q)] += l.shadow_q, gathers[static_cast<std::size_t>(l.q)] += l.share_q;
    }
  };
  add(links);
  add(unseen);
  // Top-down sums (children have larger ids than their parent); a node is shadowed when some leaf
  // below it passes the budget and it can still split.
  std::vector<double> sum(h.size(), 0.0), total(h.size(), 0.0);
  std::vector<char> over(h.size(), 0);
  for (std::size_t i = 0; i < h.size(); ++i) {
    const ElementNode& n = h.node(static_cast<NodeId>(i));
    const std::size_t parent = static_cast<std::size_t>(n.parent);
    sum[i] = own[i] + (n.parent != kNoNode ? sum[parent] : 0.0);
    total[i] = gathers[i] + (n.parent != kNoNode ? total[parent] : 0.0);
  }
  for (std::size_t i = h.size(); i-- > 0;) {
    const ElementNode& n = h.node(static_cast<NodeId>(i));
    if (n.is_leaf()) over[i] = sum[i] > kShadowBudget * total[i];
    if (over[i] && n.parent != kNoNode) over[static_cast<std::size_t>(n.parent)] = 1;
  }
  std::vector<Candidate> again;
  const auto select = [&](auto& list) {
    std::erase_if(list, [&](const auto& l) {
      const bool p =
          !is_cluster(l.p) && l.shadow_p > 0.0f && over[static_cast<std::size_t>(l.p)] && oracle.can_split(l.p);
      const bool q =
          !is_cluster(l.q) && l.shadow_q > 0.0f && over[static_cast<std::size_t>(l.q)] && oracle.can_split(l.q);
      if (!p && !q) return false;
      Candidate c;
      c.p = p ? l.p : l.q;
      c.q = p ? l.q : l.p;
      c.split_p = true;
      again.push_back(c);
      return true;
    });
  };
  select(links);
  select(unseen);
  return again;
}

}  // namespace

RefineResult refine(ElementHierarchy& h, const ClusterTree* tree, const RefinementOracle& oracle,
                    std::vector<Candidate> work, const std::function<void(std::string_view)>& progress,
                    double progress_interval_seconds) {
  RefineResult result;
  const std::size_t nodes_before = h.size();
  refine_levels(h, tree, oracle, std::move(work), progress, progress_interval_seconds, result);
  for (int pass = 0; pass < kShadowPasses; ++pass) {
    std::vector<Candidate> again = shadowed(h, oracle, result.links, result.unseen);
    if (again.empty()) break;
    if (progress)
      progress(fmt::format("refine: {} partly visible pairs under shadowed leaves refined again", again.size()));
    refine_levels(h, tree, oracle, std::move(again), progress, progress_interval_seconds, result);
  }
  result.new_nodes = h.size() - nodes_before;
  return result;
}

std::size_t directed_link_count(const std::vector<Link>& links) {
  std::size_t count = 0;
  for (const Link& l : links) count += (l.f_pq > 0.0) + (l.f_qp > 0.0);
  return count;
}

}  // namespace hrad
