// The exchange area A_p F_pq of one pair of patches, obstructed, computed once for both directions
// (A_p F_pq = A_q F_qp by construction: reciprocity is exact, not approximate).
//
//   fully visible (shaft culling with exact predicates: nothing meets the pair's shaft)
//       -> the closed form of Schroeder & Hanrahan 1993 (polygon_to_polygon() at its default
//          accuracy, ~1e-11 relative and better)
//   fully hidden -> exactly 0
//   partly visible -> the unoccluded closed form times a visible fraction:
//       sampled: kernel-weighted (Wallace, Elmquist & Haines 1989) over stratified point pairs, the
//                sample count raised fourfold until the fraction's standard error meets a target;
//       exact region: at Gauss points x_k of p, the exact part of q that x_k sees (visible_region(),
//                exact rational arithmetic) and Lambert's formula to it; the fraction is
//                sum_k w_k F(x_k -> visible q) / sum_k w_k F(x_k -> q). Visibility is exact at every
//                point; the Gauss rule integrates a continuous integrand with kinks at shadow
//                boundaries, so the remaining error is the rule's (not estimated).
// Either way 0 <= fraction <= 1, so 0 <= A_p F_pq <= its unoccluded value. No offset or epsilon is
// applied anywhere: touching and shared-edge pairs take the kernels' exact limits.
#pragma once

#include <cstdint>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/visibility/visibility.h"

namespace hrad {

enum class PartialVisibility { kSampled, kExactRegion };

/// The fewest point pairs a sampled fraction gets (4 points of p, 4 rays from each). The
/// kernel-weighted fraction is a ratio of two sums, biased by O(1 / rays); a row sums hundreds of
/// such fractions, so their biases add while their errors average out. Against a reference with
/// 100x the rays, 4 rays per pair left rows biased by +0.14 of their reported error on average
/// (rows beyond 3 reported errors: 0.7% instead of 0.27%); 16 rays remove it.
inline constexpr int kMinSampledRays = 16;

struct PairExchangeOptions {
  PartialVisibility partial = PartialVisibility::kSampled;
  /// Target standard error of a partly visible pair's visible fraction (sampled).
  double fraction_error = 0.01;
  int min_rays = 64;     ///< first round of point pairs (sampled)
  int max_rays = 4096;   ///< last round: the target may be missed there; the error says by how much
  int region_order = 2;  ///< Gauss order for the exact region: 3 order^2 points per triangle of p
  /// Relative accuracy asked of the closed form (polygon_to_polygon()) for a fully visible pair,
  /// and for a partly visible pair's unoccluded factor.
  double closed_form_tolerance = 1e-10;
  double partial_closed_form_tolerance = 1e-8;
  /// When > 0: a pair whose unobstructed factors (the closed form) are both below this is dropped
  /// before its shaft test; its result carries those factors as the most it could hold.
  double threshold = 0.0;
  /// When > 0: a pair whose unobstructed factors are both below this (and not dropped) skips the
  /// shaft test; its visible fraction is sampled with `far_rays` point pairs against the whole
  /// scene. Far pairs are most pairs of a large open model and each shaft across it meets many
  /// occluders; their factors are small, so their sampling error weighs little in a row.
  double sample_below = 0.0;
  int far_rays = 16;
};

struct PairExchange {
  double exchange = 0.0;    ///< A_p F_pq = A_q F_qp, obstructed
  double unoccluded = 0.0;  ///< the same without obstruction (0 when facing away or coplanar)
  double error = 0.0;       ///< standard error of `exchange` from sampling (0 when exact)
  PairClass pair_class = PairClass::kFacingAway;
  int rays = 0;                               ///< segments cast
  int regions = 0;                            ///< exact visible regions computed
  int closed_forms = 0;                       ///< polygon_to_polygon() calls made
  bool dropped = false;                       ///< below options.threshold both ways: exchange 0, not classified
  double dropped_pq = 0.0, dropped_qp = 0.0;  ///< if dropped: bounds of F_pq and F_qp (unobstructed)
  bool shaft_skipped = false;                 ///< below options.sample_below: sampled without a shaft test (kPartial)
};

/// Patches `p` and `q` of the evaluator's scene. The evaluator must be built with the scene's
/// visibility oracle (effects.visibility off when the scene has no occlusion). Thread-safe.
PairExchange pair_exchange(const FormFactorEvaluator& evaluator, int p, int q, const PairExchangeOptions& options);

/// pair_exchange() without sampling: a partly visible pair comes back with its class, its
/// unoccluded exchange and exchange 0, for sample_partial() once its ray budget is known (a pair
/// below options.sample_below comes back sampled).
PairExchange classify_pair(const FormFactorEvaluator& evaluator, int p, int q, const PairExchangeOptions& options);

/// The sampled visible fraction of a partly visible pair from classify_pair() with `rays` point
/// pairs (at least kMinSampledRays): sets its exchange, error and rays. Thread-safe.
void sample_partial(const FormFactorEvaluator& evaluator, int p, int q, int rays, PairExchange* pair);

}  // namespace hrad
