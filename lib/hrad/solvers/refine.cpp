#include "hrad/solvers/refine.h"

#include <algorithm>
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

// Candidates per unit of a level's sorting: a fixed size, so that what the units write, and where,
// does not depend on the thread count.
constexpr std::size_t kSortChunk = 4096;

// Where the candidates of one unit go: their links, unseen pairs and child pairs.
struct SortCounts {
  std::size_t links = 0, unseen = 0, next = 0;
};

// The side a split decision splits.
NodeRef split_side(const Candidate& c) { return c.decision == Decision::kSplitP ? c.p : c.q; }

// The pairs a decided candidate passes to the next level.
std::size_t child_count(const Candidate& c) {
  switch (c.decision) {
    case Decision::kSelf:
      return 3;
    case Decision::kSplitP:
    case Decision::kSplitQ:
      return is_cluster(split_side(c)) ? 2 : 4;
    default:
      return 0;
  }
}

// A level's pairs in chunks of at most 4 kSortChunk: chunk k holds the pairs that the k-th sort
// unit of the level before produced, allocated and written by that unit's thread. One vector
// resized by one thread was 1.4 s of the 13.4 s refinement of the generated 3,726-polygon
// warehouse at two threads (constructing the pairs and faulting their pages in).
using Level = std::vector<std::vector<Candidate>>;

std::size_t pair_count(const Level& level) {
  std::size_t n = 0;
  for (const auto& chunk : level) n += chunk.size();
  return n;
}

// A sort unit: at most kSortChunk pairs of one chunk, from `begin`; `index` is the level-wide index
// of its first pair.
struct SortUnit {
  std::size_t chunk = 0, begin = 0, end = 0, index = 0;
};

// Sorts a level's decided candidates, in their order, into the result's links and unseen pairs
// and the next level's pairs. Only the element splits are serial (the hierarchy's ids follow their
// order); the rest runs over units of a fixed size, with offsets from the units' counts. The level
// is freed chunk by chunk in parallel, its shared occluder lists' counts with it.
Level sort_decided(ElementHierarchy& h, const ClusterTree* tree, Level& level, RefineResult& result) {
  std::vector<SortUnit> units;
  std::size_t n = 0;
  for (std::size_t k = 0; k < level.size(); ++k)
    for (std::size_t b = 0; b < level[k].size(); b += kSortChunk) {
      units.push_back({k, b, std::min(level[k].size(), b + kSortChunk), n});
      n += units.back().end - b;
    }
  std::vector<NodeId> first(n, kNoNode);  // an element split's first child, by level-wide index
  for (const SortUnit& u : units)
    for (std::size_t i = u.begin; i < u.end; ++i) {
      const Candidate& c = level[u.chunk][i];
      if (c.decision != Decision::kSplitP && c.decision != Decision::kSplitQ) continue;
      ++result.splits;
      if (!is_cluster(split_side(c))) first[u.index + i - u.begin] = h.split(split_side(c));
    }
  std::vector<SortCounts> at(units.size() + 1);
  tbb::parallel_for(std::size_t{0}, units.size(), [&](std::size_t k) {
    SortCounts& count = at[k + 1];
    for (std::size_t i = units[k].begin; i < units[k].end; ++i) {
      const Candidate& c = level[units[k].chunk][i];
      count.links += c.decision == Decision::kLink;
      count.unseen += c.decision == Decision::kUnseen;
      count.next += child_count(c);
    }
  });
  Level next(units.size());
  at[0] = {result.links.size(), result.unseen.size(), 0};
  for (std::size_t k = 0; k < units.size(); ++k) {
    at[k + 1].links += at[k].links;
    at[k + 1].unseen += at[k].unseen;
  }
  result.links.resize(at[units.size()].links);
  result.unseen.resize(at[units.size()].unseen);
  tbb::parallel_for(std::size_t{0}, units.size(), [&](std::size_t k) {
    const SortUnit& u = units[k];
    std::vector<Candidate>& children = next[k];
    children.reserve(at[k + 1].next);
    SortCounts to = at[k];
    for (std::size_t i = u.begin; i < u.end; ++i) {
      Candidate& c = level[u.chunk][i];
      switch (c.decision) {
        case Decision::kDrop:
          break;
        case Decision::kUnseen:
          result.unseen[to.unseen++] = {c.p, c.q, c.shadow_p, c.shadow_q, c.share_p, c.share_q};
          break;
        case Decision::kLink:
          result.links[to.links++] = {c.p,
                                      c.q,
                                      c.f_pq,
                                      c.f_qp,
                                      c.partial,
                                      c.fraction,
                                      std::move(c.hidden_p),
                                      std::move(c.hidden_q),
                                      c.shadow_p,
                                      c.shadow_q,
                                      c.share_p,
                                      c.share_q,
                                      c.shaped,
                                      c.shape_p,
                                      c.shape_q,
                                      c.source_p,
                                      c.source_q};
          break;
        case Decision::kSelf: {
          const Cluster& cluster = tree->cluster(cluster_index(c.p));
          children.push_back(child_of(c, cluster.children[0], cluster.children[0]));
          children.push_back(child_of(c, cluster.children[1], cluster.children[1]));
          children.push_back(child_of(c, cluster.children[0], cluster.children[1]));
          break;
        }
        case Decision::kSplitP:
        case Decision::kSplitQ: {
          const bool split_p = c.decision == Decision::kSplitP;
          auto add = [&](NodeRef child) {
            children.push_back(split_p ? child_of(c, child, c.q) : child_of(c, c.p, child));
          };
          if (is_cluster(split_side(c))) {
            const Cluster& cluster = tree->cluster(cluster_index(split_side(c)));
            add(cluster.children[0]);
            add(cluster.children[1]);
          } else {
            const NodeId split = first[u.index + i - u.begin];
            for (NodeId child = 0; child < 4; ++child) add(split + child);
          }
          break;
        }
      }
    }
  });
  tbb::parallel_for(std::size_t{0}, level.size(), [&](std::size_t k) { std::vector<Candidate>().swap(level[k]); });
  std::erase_if(next, [](const std::vector<Candidate>& chunk) { return chunk.empty(); });
  return next;
}

// Refines `work` breadth-first until every pair is linked or dropped (see refine()).
void refine_levels(ElementHierarchy& h, const ClusterTree* tree, const RefinementOracle& oracle,
                   std::vector<Candidate> first, const std::function<void(std::string_view)>& progress,
                   double progress_interval, RefineResult& result) {
  Level work;
  work.push_back(std::move(first));
  int level = 0;
  for (std::size_t size = pair_count(work); size > 0;) {
    // A level of a large scene takes minutes: its pairs decided so far, with an estimate.
    ProgressReporter decided(fmt::format("refine: level {}", level + 1), size, "pairs", progress, progress_interval);
    tbb::parallel_for(std::size_t{0}, work.size(), [&](std::size_t k) {
      std::vector<Candidate>& chunk = work[k];
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunk.size(), 16),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i) oracle.decide(chunk[i]);
                          decided.advance(range.size());
                        });
    });
    result.candidates += size;
    Level next = sort_decided(h, tree, work, result);
    const std::size_t next_size = pair_count(next);
    ++level;
    // Levels too short to show progress stay quiet.
    if (progress && decided.lines() > 0)
      progress(fmt::format("refine: level {}: {} pairs examined, {} links, {} elements, {} pairs next", level, size,
                           result.links.size(), h.size(), next_size));
    work = std::move(next);
    size = next_size;
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
std::vector<Candidate> shadowed(const ElementHierarchy& h, const RefinementOracle& oracle, LinkVector& links,
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

std::size_t directed_link_count(const LinkVector& links) {
  std::size_t count = 0;
  for (const Link& l : links) count += (l.f_pq > 0.0) + (l.f_qp > 0.0);
  return count;
}

}  // namespace hrad
