// Links at any level of the hierarchy, gathered where they are stored: the link operator of
// Hanrahan, Salzman & Aupperle 1991 ("GatherRad"), with Smits, Arvo & Greenberg 1994's cluster
// links. One gather touches each directed link once: its work is the number of links.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "hrad/solvers/cluster_transfer.h"
#include "hrad/solvers/cluster_tree.h"
#include "hrad/solvers/link_operator.h"
#include "hrad/solvers/refine.h"

namespace hrad {

class HsaLinks final : public LinkOperator {
 public:
  /// Stores both directions of every link in `links` that carries a factor, grouped by receiver:
  /// 76 bytes per link between elements (32-bit source, the factor's shape over the receiver and
  /// the source points' weights, Link::shape_p and source_q, as 9 floats each: 6e-8 relative, far
  /// below any tolerance), 56 per link with a cluster end (32-bit source, float factor, the unit
  /// direction to the source, the inverse of the source's projected area towards the receiver, and
  /// the lists of patches on either end that see nothing of the other, usually none). `tree` may be null when no link
  /// has a cluster end.
  HsaLinks(const std::vector<Link>& links, const ElementHierarchy& hierarchy, const ClusterTree* tree,
           const ClusterTransfer& geometry);

  /// Not reentrant: a cluster receiver's links keep what they carry in a buffer of the operator
  /// between the gather's two phases.
  void gather(NodeField& field) const override;
  /// Eighteen per link between elements (the radiosity the source sends, from its moments, then
  /// the receiver's field at its points); per link with a cluster end one, plus one per patch of a
  /// cluster source (what it shows) and of a cluster receiver (each patch's share).
  std::uint64_t terms() const override { return 18 * links_.size() + cluster_terms_; }
  std::uint64_t bytes() const override;

 private:
  struct DirectedLink {
    std::int32_t source;          ///< dense node index
    std::array<float, 9> factor;  ///< the factor at the receiver's points (link_operator.h PointValues)
    std::array<float, 9> weight;  ///< the source's shape over the exchange: sum_i weight_i m_i is the radiosity sent
  };
  /// A link with a cluster end. A cluster source shows the mean radiosity of its patches weighted
  /// by their projected areas towards the receiver, A_j max(0, n_j.u) (Sillion 1995's oriented
  /// clusters, with each patch's exact projected area); a cluster receiver shares the power A_R F B
  /// among its patches in proportion to their projected areas towards the source, so that a patch
  /// facing away gets nothing and the shares sum to that power. Patches that see nothing of the
  /// other end (Link::hidden_p) neither show nor receive.
  struct ClusterLink {
    std::int32_t source;
    /// F for an element receiver; A_R F / (projected area of R towards the source) for a cluster
    /// receiver, whose patch i then gets factor max(0, n_i.u) times what the source shows.
    float factor;
    std::array<float, 3> to_source;  ///< unit direction u from the receiver's centre to the source's
    float source_scale;              ///< 1 / the source's projected area towards the receiver (cluster sources)
  };
  static_assert(sizeof(DirectedLink) == 76);
  static_assert(sizeof(ClusterLink) == 24);

  /// What the source of cluster link k shows towards its receiver.
  Rgb shown(const NodeField& field, std::uint64_t k) const;

  std::size_t elements_ = 0;
  const Scene& scene_;
  const ClusterTree* tree_ = nullptr;
  const ElementHierarchy& h_;
  std::vector<std::uint64_t> offsets_, cluster_offsets_;  ///< per dense receiver, + 1
  std::vector<DirectedLink> links_;
  std::vector<ClusterLink> cluster_links_;
  std::uint64_t cluster_terms_ = 0;
  std::uint64_t hidden_bytes_ = 0;  ///< the hidden patches' lists (shared with the links)
  bool cluster_receivers_ = false;  ///< some link has a cluster receiver
  /// Per cluster link: the receiver's and the source's patches that take no part (Link::hidden_p).
  std::vector<std::shared_ptr<const std::vector<int>>> receiver_hidden_, source_hidden_;
  mutable std::vector<Rgb> carried_;  ///< per cluster link of a cluster receiver: factor times what the source shows
};

}  // namespace hrad
