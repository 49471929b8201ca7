// Dense links that carry fields, for linear elements (linear_basis.h) in the full matrix and
// substructuring: each (receiver, source) entry holds the factor from each of the receiver's
// simpson_points() to the source, F(dA_x -> source) V(x, source) by Lambert's exact point-to-polygon
// formula (FormFactorEvaluator::point_factor(), its one-sided limit on the receiver's boundary), and
// the source's shape towards the receiver, F(dA_y -> receiver) V(y, receiver) at the source's points,
// over which the source's radiosity moments are weighed (link_operator.h NodeField::radiosity_moments).
// The kernel over the pair is thus the separable K(x, y) ~ F(x -> source) w(y), as for the hierarchical
// solver's shaped links (refinement_oracle.h), with the receiver's side exact at every point.
//
// Why exact point factors rather than a pair mean spread over a shape: at every receiver point the
// factors to sources that tile a closed room sum to 1 (Lambert's formula is exact per point), so a
// uniform room's field is E / (1 - rho) at every point to rounding; and the source's weights are
// normalised so that a uniform source sends its radiosity. What the quadrature leaves is reciprocity,
// which holds to the points' quadrature error.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "hrad/core/huge_page_allocator.h"
#include "hrad/formfactor/simpson_rule.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/solvers/link_operator.h"
#include "hrad/solvers/near_field_rule.h"

namespace hrad {

/// The unoccluded factors F(dA_x -> source) at the receiver's simpson_points() (PointValues order;
/// `count` of them): Lambert's formula at the centre, its one-sided limit from inside the receiver
/// at the boundary points (a point on an edge shared with the source's plane).
struct PointFactors {
  SimpsonPoints points;
  std::array<double, 9> factor{};
};
PointFactors point_factors(const FormFactorEvaluator& evaluator, const ElementNode& receiver,
                           std::span<const Vec3> source);

/// One direction of a pair: what `receiver` gathers from `source`.
struct FieldEntry {
  std::array<double, 9> factor{};  ///< F(x_k -> source) V at the receiver's points (link_operator.h PointValues)
  /// The radiosity the source sends is sum_m weight_m m_m over its moments: its points' factors
  /// towards the receiver over their integral, so that a uniform radiosity B sends B.
  std::array<double, 9> weight{};
};

/// Both directions of the pair (a, b): a's entry gathering from b and b's from a. Zero factors for
/// coplanar, facing-away and hidden pairs. A partly visible pair's points take their visible
/// fractions from `rays` rays each towards the other side (deterministic in the pair's geometry);
/// points on a boundary cast them from just inside the element. Thread-safe.
void pair_fields(const FormFactorEvaluator& evaluator, const ElementNode& a, const ElementNode& b, int rays,
                 FieldEntry* a_from_b, FieldEntry* b_from_a);

/// Where an element's nine points cannot integrate a near pair: the near_field_rule() of each end of
/// every pair of `receivers` x `sources` closer than their size (FormFactorEvaluator::separated() at
/// 1, either way), one floating in front of the other (no vertex within kContactTolerance of its
/// plane), whose points' mean factor strays from the closed form by more than kNearFieldStray on
/// either end; driven by its factors to all such partners.
class NearFieldRules {
 public:
  NearFieldRules(const FormFactorEvaluator& evaluator, const ElementHierarchy& hierarchy,
                 std::span<const NodeId> receivers, std::span<const NodeId> sources);
  /// The rule of node `n`, or null.
  const std::vector<RulePoint>* rule(NodeId n) const;
  std::size_t nodes() const { return rules_.size(); }

 private:
  std::unordered_map<NodeId, std::vector<RulePoint>> rules_;
};

/// The relative stray of a near pair's nine-point factor from the closed form above which its ends
/// take near-field rules. A lamp 1 mm in front of a wall strays by 2-4x; pairs that stray less keep
/// their nine points, whose reciprocity errs then about as the far pairs' quadrature does.
inline constexpr double kNearFieldStray = 0.05;
/// A near-field rule integrates the factors to its sources to this times the element's area.
inline constexpr double kNearFieldRuleTolerance = 1e-5;

class FieldLinks final : public LinkOperator {
 public:
  /// Entries receivers x sources, zero until filled through entry(). Huge pages (BigVector).
  FieldLinks(std::vector<NodeId> receivers, std::vector<NodeId> sources);

  FieldEntry& entry(std::size_t receiver, std::size_t source) { return entries_[receiver * sources_.size() + source]; }
  const std::vector<NodeId>& receivers() const { return receivers_; }
  const std::vector<NodeId>& sources() const { return sources_; }

  /// Each receiver's irradiance at its points: sum over sources of factor_k times the radiosity the
  /// source sends. Parallel over receivers, the same bits at any thread count.
  void gather(NodeField& field) const override;
  /// Eighteen per entry, as for the hierarchical solver's shaped links (hsa_links.h).
  std::uint64_t terms() const override { return 18 * entries_.size(); }
  std::uint64_t bytes() const override { return entries_.size() * sizeof(FieldEntry); }

 private:
  std::vector<NodeId> receivers_, sources_;
  BigVector<FieldEntry> entries_;
};

/// After every pair of `links` is filled: each receiver with a rule gathers from every source it sees
/// with the moments of its factor by the rule (near_field_rule.h: all of its pairs, so that at each of
/// the rule's points its factors keep their closure), visibility by one ray a rule point where the pair
/// is partly visible; and its weights as a source of `links` take the same moments (normalised).
/// Parallel over the ruled receivers; deterministic.
void apply_near_field_rules(const FormFactorEvaluator& evaluator, const ElementHierarchy& hierarchy,
                            const NearFieldRules& rules, FieldLinks& links);

/// Rays per point of a partly visible pair for `visibility_samples` point pairs per pair (the
/// constant elements' budget): a quarter of it, at least 4, so that a pair's 18 points cost a few
/// times what one pair's fraction costs.
inline int field_rays_per_point(int visibility_samples) {
  return visibility_samples / 4 > 4 ? visibility_samples / 4 : 4;
}

}  // namespace hrad
