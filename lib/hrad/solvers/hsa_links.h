// Links at any level of the hierarchy, gathered where they are stored: the link operator of
// Hanrahan, Salzman & Aupperle 1991 ("GatherRad"), with Smits, Arvo & Greenberg 1994's cluster
// links. One gather touches each directed link once: its work is the number of links.
#pragma once

#include <array>
#include <cstdint>
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
  /// below any tolerance), 20 per link with a
  /// cluster end (32-bit source, float factor and the unit direction to the source, which picks the
  /// surfaces that send and receive). `tree` may be null when no link has a cluster end.
  HsaLinks(const std::vector<Link>& links, const ElementHierarchy& hierarchy, const ClusterTree* tree,
           const ClusterTransfer& geometry);

  void gather(NodeField& field) const override;
  /// Eighteen per link between elements (the radiosity the source sends, from its moments, then
  /// the receiver's field at its points), one per cluster link.
  std::uint64_t terms() const override { return 18 * links_.size() + cluster_links_.size(); }
  std::uint64_t bytes() const override;

 private:
  struct DirectedLink {
    std::int32_t source;           ///< dense node index
    std::array<float, 9> factor;   ///< the factor at the receiver's points (link_operator.h PointValues)
    std::array<float, 9> weight;   ///< the source's shape over the exchange: sum_i weight_i m_i is the radiosity sent
  };
  struct ClusterLink {
    std::int32_t source;
    float factor;
    std::array<float, 3> to_source;  ///< unit direction from the receiver's centre to the source's
  };
  static_assert(sizeof(DirectedLink) == 76);
  static_assert(sizeof(ClusterLink) == 20);

  Rgb shown(const NodeField& field, std::size_t source, const std::array<float, 3>& towards) const;

  std::size_t elements_ = 0;
  const ClusterTree* tree_ = nullptr;
  const ElementHierarchy& h_;
  std::vector<std::uint64_t> offsets_, cluster_offsets_;  ///< per dense receiver, + 1
  std::vector<DirectedLink> links_;
  std::vector<ClusterLink> cluster_links_;
};

}  // namespace hrad
