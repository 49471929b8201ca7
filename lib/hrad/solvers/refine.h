// Refinement of node pairs into links (Hanrahan, Salzman & Aupperle 1991, "Refine"), breadth-first
// and deterministic: all candidates of one level are examined in parallel (the oracle only reads),
// then their element splits are made in order, and they are sorted into links and the next level's
// pairs in fixed chunks at offsets from the chunks' counts, so the links do not depend on the thread
// count.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <utility>
#include <vector>

#include "hrad/core/huge_page_allocator.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/cluster_tree.h"
#include "hrad/solvers/refinement_oracle.h"

namespace hrad {

/// A stored interaction between p and q, gathered both ways: p gathers f_pq B_q, q gathers f_qp B_p.
/// Between elements it also carries the factor's shape over each side (Candidate::shape_p).
struct Link {
  NodeRef p = kNoNode;
  NodeRef q = kNoNode;
  double f_pq = 0.0;
  double f_qp = 0.0;
  bool partial = false;
  double fraction = 1.0;                                                        ///< Candidate::fraction
  std::shared_ptr<const ShadedPatches> hidden_p = nullptr, hidden_q = nullptr;  ///< Candidate::hidden_p, hidden_q
  float shadow_p = 0.0f, shadow_q = 0.0f;                                       ///< Candidate::shadow_p, shadow_q
  float share_p = 0.0f, share_q = 0.0f;                                         ///< Candidate::share_p, share_q
  bool shaped = false;
  std::array<float, 9> shape_p{}, shape_q{};
  /// Between elements: what p sends through the link is sum_i source_p[i] m_i over the moments of
  /// its radiosity (link_operator.h): shape_p over the exchange. The same for q.
  std::array<float, 9> source_p{}, source_q{};
};

/// The links of a refinement: GBs on large scenes, in huge pages (huge_page_allocator.h), whose
/// fewer page faults make growing them cheaper for the one thread that does.
using LinkVector = BigVector<Link>;

/// A pair decided Decision::kUnseen (p, q as examined), with the shadow errors and shares its test
/// found: they count in the shadow passes as a link's do (refine.cpp, shadowed()).
struct UnseenPair {
  NodeRef p = kNoNode;
  NodeRef q = kNoNode;
  float shadow_p = 0.0f, shadow_q = 0.0f;
  float share_p = 0.0f, share_q = 0.0f;
};

struct RefineResult {
  LinkVector links;
  /// The pairs decided Decision::kUnseen that no shadow pass refined again.
  std::vector<UnseenPair> unseen;
  std::uint64_t candidates = 0;  ///< pairs the oracle examined
  std::size_t splits = 0;        ///< split decisions (new or existing children)
  std::size_t new_nodes = 0;     ///< elements the hierarchy grew by
};

/// Refines `work` until every pair is linked or dropped. `tree` may be null when no candidate has
/// a cluster. `progress` (may be empty) gets one line per level.
///
/// Then the shadows: each link's error is within the tolerance, but the errors of partly visible
/// links at a receiver and its ancestors share a sign where an occluder hides many sources at once,
/// so on a leaf in an umbra they add up (a leaf inherits every coarse partial link's mean
/// visibility). Their sum is pushed down the quadtrees; where it exceeds kShadowBudget of what the
/// leaf gathers (its links' factors in the same weighted units, summed the same way), the partial
/// links of its ancestors are refined again with the receiver split, up to kShadowPasses times.
RefineResult refine(ElementHierarchy& hierarchy, const ClusterTree* tree, const RefinementOracle& oracle,
                    std::vector<Candidate> work, const std::function<void(std::string_view)>& progress,
                    double progress_interval_seconds = 2.0);

/// Re-refinement passes of refine() for shadowed leaves.
inline constexpr int kShadowPasses = 3;
/// A leaf is shadowed when its partial links' summed shadow errors pass this fraction of what it
/// gathers.
inline constexpr double kShadowBudget = 0.05;

/// Directed links: both directions of every link that carries a factor.
std::size_t directed_link_count(const LinkVector& links);

}  // namespace hrad
