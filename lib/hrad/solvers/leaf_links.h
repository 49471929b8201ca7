// Links resolved to the leaves on both sides (`--push leaf`): HSA's push and pull with each leaf's own
// factor. Exact per element in closed rooms, at a cost of one term per (leaf, link of the leaf or of
// an ancestor): about n times the links on a leaf's path, not O(links) (hsa_links.h is).
//
// HSA 1991 gather at the link's receiver, an interior node a, and push the gathered irradiance
// F(a -> q) B_q down to every leaf below a unchanged. A leaf thus receives its ancestors' average
// factors, so the factors one leaf gathers through (its own links and its ancestors') do not sum
// to its true total: in a closed room they sum to 1 per patch (the links tile patch x room) but
// from 0.8 to 1.24 per element, which put corner elements 5% off at rho = 0.9 and could make
// Jacobi diverge as rho -> 1. The source side has the same defect: q's mean B_q weights q's
// leaves by area, not by how much each sends to a, so the power a leaf sends through its
// ancestors' links is off by the same factor (1.5% of a tiny light's power went missing in a
// 1 km room whose floor is lit unevenly).
//
// Here each link (p, q) keeps its level, its visible fraction and its total exchange
// A_p F(p -> q) = A_q F(q -> p), but is resolved on both sides to the leaves below p and q with
// the leaves' own unoccluded factors f(L -> q), f(M -> p) (receiver_gauss_factor(): Gauss points
// on the leaf, Lambert's point-to-polygon formula at each), scaled so that sum_L A_L f(L -> q) = A_p F(p -> q) exactly.
// The link's leaf-to-leaf block is approximated by the separable K(L, M) = f(L -> q) w_M, w_M = A_M f(M -> p) / (A_q
// F(q -> p)): leaf L gathers f(L -> q) times the w-weighted mean of q's leaves. Its rows sum to f(L -> q) (closure: a
// leaf's factors to sources tiling a closed room sum to 1 up to the rule, since Lambert's formula is exact at each
// point) and its columns carry A_M f(M -> p) (reciprocity per leaf, so power balances exactly). A side that is a leaf
// keeps the exact analytic factor. Cost: one term per (leaf, link of the leaf or of an ancestor), computed once per
// refinement in parallel, and two passes over them per iteration. A leaf far from the other side against its size takes
// its factor at its centroid (receiver_factor_by_distance()); the gather reads the factors grouped by leaf, in sequence
// (hierarchical_benchmark measures it).
//
// With linear elements (`fields`) each entry keeps its leaf's factors at the leaf's simpson_points()
// (field_links.h point_factors(): Lambert's exact point factor at each) times the link's visible
// fraction, unscaled: a leaf gathers a field, which the push projects onto its linear space
// (linear_basis.h), and a side sends its leaves' radiosity moments weighed by their point factors
// over those factors' integral (field_links.h's source weights, summed over the side). As for the
// full matrix, each leaf point sums the exact factors of sources that tile a closed room, so a
// uniform room is reproduced at every point; reciprocity holds to the points' quadrature. The HSA
// push instead interpolates a coarse link's field down to the leaves, which misses fields that
// vary like a logarithm (beside a room's edges corners stray by a few percent).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "hrad/core/huge_page_allocator.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/solvers/link_operator.h"
#include "hrad/solvers/refine.h"

namespace hrad {

/// The link pairs resolved to leaves. Pair k's p side is entries [pairs[k].p_first, + p_count),
/// its q side [q_first, + q_count); `leaf` and `weight` are in this entry order (each side's mean
/// reads them). The factors are stored grouped by leaf for the gather, which then reads them in
/// sequence: leaf n's are [leaf_offsets[n], leaf_offsets[n + 1]) of `factor` and `other_side`,
/// in increasing entry order. 24 bytes per entry plus 8 per node.
class LeafLinks final : public LinkOperator {
 public:
  /// Resolves `links` (between elements only) to leaves as described above, with point fields
  /// for linear elements when `fields`. Deterministic order.
  LeafLinks(const ElementHierarchy& hierarchy, const FormFactorEvaluator& evaluator, std::span<const Link> links,
            bool fields = false);

  /// For every pair adds to each leaf L of one side f(L -> other) times the weighted mean radiosity
  /// of the other side's leaves (all channels). Parallel (the sides' means over pairs, then each
  /// leaf's sum over its entries in entry order): the same bits at any thread count.
  void gather(NodeField& field) const override;
  /// Two per entry: its share of its side's mean, and its factor times the other side's mean; with
  /// fields, one per moment the leaf sends and one per point it gathers at.
  std::uint64_t terms() const override { return (fields_ ? 18 : 2) * leaf_.size(); }
  std::uint64_t bytes() const override;
  std::size_t size() const { return leaf_.size(); }

 private:
  struct Pair {
    std::size_t p_first = 0, p_count = 0, q_first = 0, q_count = 0;
    /// Side 0 (p) or 1 (q) as [first, end).
    std::pair<std::size_t, std::size_t> side(std::size_t s) const {
      return s == 0 ? std::pair{p_first, p_first + p_count} : std::pair{q_first, q_first + q_count};
    }
  };
  void gather_fields(NodeField& field) const;

  std::size_t nodes_ = 0;
  bool fields_ = false;
  std::vector<Pair> pairs_;
  BigVector<NodeId> leaf_;    ///< the leaf of each entry
  BigVector<double> weight_;  ///< A_leaf f / (A_p F(p -> q)): the leaf's share of its side's exchange
  std::vector<std::uint64_t> leaf_offsets_;
  /// By leaf: f(leaf -> the other side's node), visible fraction included, and which side's mean
  /// it gathers (2 k for pair k's q side, 2 k + 1 for its p side).
  BigVector<double> factor_;
  BigVector<std::uint32_t> other_side_;
  /// With fields, by entry: the point factors (floats: 6e-8 relative), which also weigh the leaf's
  /// moments when its side sends; by leaf, like factor_: the entry. Per side (2 k: pair k's q side,
  /// 2 k + 1: its p side): 1 / the side's point factors' integral against its leaves' bases.
  BigVector<std::array<float, 9>> points_;
  BigVector<std::uint64_t> entry_;
  std::vector<double> inverse_integral_;
  std::vector<std::uint8_t> functions_;  ///< per node: its basis functions (9 quad, 6 triangle)
};

}  // namespace hrad
