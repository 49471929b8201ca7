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
  /// below any tolerance), 32 per link with a cluster end (32-bit source, float factor, the inverse
  /// of the source's weight, the offsets of both ends' weights) and 4 bytes per patch of each
  /// cluster end for its weight, shared by both directions. `tree` may be null when no link has a
  /// cluster end.
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
  /// A link with a cluster end. Each cluster end shares the link among its patches by weights A_j
  /// q_j (ClusterTransfer::link_weights(): each patch's factor to the other end's bounding sphere
  /// times the part of the other end it sees; Sillion 1995's oriented clusters, per patch): a
  /// cluster source shows the mean radiosity of its patches by these weights, a cluster receiver
  /// gives patch j the share A_j q_j / W of the power A_R F B it receives. The two directions of a
  /// link use the same weights of each end, so the link is reciprocal patch by patch, and the shares
  /// sum to what the link carries.
  struct ClusterLink {
    std::int32_t source;
    /// F for an element receiver; A_R F / W_R for a cluster receiver, whose patch j then gets q_j
    /// times what the source shows.
    float factor;
    float source_scale;            ///< 1 / W_S of a cluster source
    std::uint64_t receiver_q = 0;  ///< a cluster receiver's q_j: weights_[receiver_q + j]
    std::uint64_t source_q = 0;    ///< a cluster source's q_j: weights_[source_q + j]
  };
  static_assert(sizeof(DirectedLink) == 76);
  static_assert(sizeof(ClusterLink) == 32);

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
  bool cluster_receivers_ = false;  ///< some link has a cluster receiver
  std::vector<float> weights_;      ///< per cluster end of a link, its patches' q_j in tree order
  /// Per patch: its index in the patch list of each cluster above it is position_[p] - begin.
  std::vector<int> position_;
  mutable std::vector<Rgb> carried_;  ///< per cluster link of a cluster receiver: factor times what the source shows
};

}  // namespace hrad
