// Links at any level of the hierarchy, gathered where they are stored: the link operator of
// Hanrahan, Salzman & Aupperle 1991 ("GatherRad"), with Smits, Arvo & Greenberg 1994's cluster
// links. One gather touches each directed link once: its work is the number of links.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

#include "hrad/core/huge_page_allocator.h"
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
  /// below any tolerance), 24 per link with a cluster end (32-bit source, float factor, the offsets
  /// of both ends' weights) and 4 bytes per patch of each cluster end for its weight (8 where it
  /// gets by its facing weights), shared by both directions. `tree` may be null when no link has a
  /// cluster end.
  HsaLinks(const LinkVector& links, const ElementHierarchy& hierarchy, const ClusterTree* tree,
           const ClusterTransfer& geometry);

  /// Not reentrant: a cluster receiver's links keep what they carry in a buffer of the operator
  /// between the gather's two phases.
  void gather(NodeField& field) const override;
  /// Eighteen per link between elements (the radiosity the source sends, from its moments, then
  /// the receiver's field at its points); per link with a cluster end one, plus one per patch of a
  /// cluster source (what it shows) and of a cluster receiver (each patch's share).
  std::uint64_t terms() const override { return 18 * links_.size() + cluster_terms_; }
  std::uint64_t bytes() const override;

  /// The adjoint of the gather over the links between elements: per element (by node id), the
  /// coefficients d with sum_i d_i m_i the power those links deliver from the element's radiosity
  /// moments m (what the element sends through them). `received(r, factor)` is a receiver's area
  /// times the mean over it of a factor field at its points.
  template <class Received>
  std::vector<std::array<double, 9>> send_coefficients(Received received) const {
    std::vector<std::array<double, 9>> d(elements_, std::array<double, 9>{});
    for (std::size_t r = 0; r < elements_; ++r)
      for (std::uint64_t k = offsets_[r]; k < offsets_[r + 1]; ++k) {
        const DirectedLink& l = links_[k];
        const double exchange = received(static_cast<NodeId>(r), l.factor);
        std::array<double, 9>& s = d[static_cast<std::size_t>(l.source)];
        for (int i = 0; i < 9; ++i) s[static_cast<std::size_t>(i)] += exchange * static_cast<double>(l.weight[i]);
      }
    return d;
  }
  /// The same for the links with a cluster end, which read a source element's (or a cluster
  /// source's patches') mean radiosity: per element (by node id), what its uniform unit radiosity
  /// sends through them per unit of its area (the patches of a cluster source at their roots).
  std::vector<double> cluster_sends() const;

 private:
  struct DirectedLink {
    std::int32_t source;          ///< dense node index
    std::array<float, 9> factor;  ///< the factor at the receiver's points (link_operator.h PointValues)
    std::array<float, 9> weight;  ///< the source's shape over the exchange: sum_i weight_i m_i is the radiosity sent
  };
  /// A link with a cluster end. A cluster end weighs its patches j (ClusterTransfer::
  /// link_weights()). What it sends: q_j = F(j -> the other end), sampled by rays of its own
  /// (FormFactorEvaluator::shaded_surfaces(), independent of the samples that decided the link), so
  /// that the link carries sum_j A_j q_j B_j, an unbiased estimate of the power its patches send to
  /// the other end whatever their radiosities (normalising the q_j to the link's factor would make
  /// each patch's part a ratio of estimates, biased against the patches whose rays vary most). What
  /// it gets: by the same q_j, normalised (by reciprocity patch j gathers A_j F(j -> the other end)
  /// of the other end's radiosity): patch j gets A_j q_j / W of the power the link brings, W = sum
  /// A_j q_j, so nothing the link carries is lost. Only where none of the end's rays reached the
  /// other end, by each patch's factor to the other end's bounding sphere times the part of the
  /// other end it sees (Sillion 1995's oriented clusters, per patch): such a deterministic estimate
  /// of the factor misplaced up to 2.6% of a cell's radiosity beside blocks in a uniform closed room
  /// (tests/hard/clustered_room_power_test.cpp). An element source sends A_R F B through its factor F.
  struct ClusterLink {
    std::int32_t source;
    /// Per unit of what the source sends (sum_j A_j q_j B_j of a cluster source, B of an element
    /// source with A_R F folded in): 1 / A_R for an element receiver; 1 / W_R for a cluster
    /// receiver, whose patch j then gets q_j times it.
    float factor;
    std::uint64_t receiver_q;  ///< a cluster receiver's q_j (what it gets): weights_[receiver_q + j]
    std::uint64_t source_q;    ///< a cluster source's q_j (what it sends): weights_[source_q + j]
  };
  static_assert(sizeof(DirectedLink) == 76);
  static_assert(sizeof(ClusterLink) == 24);
  static_assert(std::is_trivially_default_constructible_v<DirectedLink> &&
                std::is_trivially_default_constructible_v<ClusterLink>);  // BigVector leaves them unwritten

  /// What the source of cluster link k sends towards its receiver, per unit of the factor.
  Rgb shown(const NodeField& field, std::uint64_t k) const;

  std::size_t elements_ = 0;
  const Scene& scene_;
  const ClusterTree* tree_ = nullptr;
  const ElementHierarchy& h_;
  std::vector<std::uint64_t> offsets_, cluster_offsets_;  ///< per dense receiver, + 1
  // Huge pages, and written once each by the parallel build (huge_page_allocator.h): GBs on
  // large scenes, whose zero-filling by one thread was most of the build.
  BigVector<DirectedLink> links_;
  BigVector<ClusterLink> cluster_links_;
  std::uint64_t cluster_terms_ = 0;
  bool cluster_receivers_ = false;  ///< some link has a cluster receiver
  BigVector<float> weights_;        ///< per cluster end of a link, its patches' two q_j in tree order
  /// Per patch: its index in the patch list of each cluster above it is position_[p] - begin.
  std::vector<int> position_;
  mutable std::vector<Rgb> carried_;  ///< per cluster link of a cluster receiver: factor times what the source shows
};

}  // namespace hrad
