// The obstructed view-factor matrix between the units of a scene (input faces, groups, View3D
// surfaces), with the guarantees thermal codes rely on:
//   * 0 <= F_uv, and F_uv <= its unobstructed value (visible fractions lie in [0, 1]);
//   * reciprocity: every pair of patches is computed once and gives E_uv = A_u F_uv = A_v F_vu,
//     stored once; the matrix holds F_uv = E_uv / A_u, so |A_u F_uv - A_v F_vu| is rounding only;
//   * closure where visibility is exact: rows of a closed enclosure whose pairs are all classified
//     exactly (fully visible or hidden) sum to 1 to the closed form's accuracy; an open model's
//     remainder 1 - sum_v F_uv is what the face sends to the sky;
//   * no row above 1: a row whose estimated (sampled) entries would take it above 1 has them
//     scaled down symmetrically until it sums to 1 (cap_rows() in the .cpp; `capped` says how
//     much each row lost);
//   * no dependence on the unit of length and no epsilon offsets (pair_exchange.h).
// With a threshold T, a pair whose unobstructed factors are below T both ways is dropped before
// its shaft test: first by a cheap bound from distance and heights (pair_bound.h), then by its
// closed form. Each row reports the sum of what it dropped (those bounds), the most factor it could
// have lost: its row sum plus that bound is at least its true row sum.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "hrad/core/progress.h"
#include "hrad/core/scene.h"
#include "hrad/viewfactors/pair_exchange.h"
#include "hrad/viewfactors/surface_units.h"

namespace hrad {

/// Pairs drawn at random before the computation and screened as it screens them: estimates of how
/// many pairs the matrix will store and how many wait for rays (with row_error), for refusing work
/// the machine cannot hold before it starts (view_factor_work.h).
struct PairSample {
  double pairs = 0.0;     ///< eligible pairs in all
  double stored = 0.0;    ///< pairs estimated to be stored (share + 3 standard errors, times pairs)
  double deferred = 0.0;  ///< of those, partly visible pairs waiting for their rays (row_error)
  int sampled = 0;        ///< pairs drawn
};

/// Pairs drawn for the PairSample.
inline constexpr std::uint64_t kWorkSamples = 4096;

struct ViewFactorOptions {
  PairExchangeOptions pair;
  /// Drop pairs whose unobstructed factor is below this in both directions (0: none).
  double threshold = 0.0;
  /// Pairs whose unobstructed factor is below this both ways (and at least the threshold) skip the
  /// shaft test and are sampled with pair.far_rays rays against the whole scene (0: none).
  double sample_below = 0.0;
  /// When > 0 (sampled partial visibility): the target standard error of each row sum's sampled
  /// part, in factor units, instead of pair.fraction_error per pair. Partly visible pairs are
  /// sampled after all pairs are classified, each with rays in proportion to its unoccluded
  /// factor and to its rows' unoccluded partly visible sums (at most pair.max_rays).
  double row_error = 0.0;
  /// Decide occluders that touch a pair's shaft exactly (VisibilityOptions::exact_shaft_contacts):
  /// more pairs classified exactly, at a higher classification cost.
  bool exact_shaft_contacts = true;
  int threads = 0;  ///< 0: all cores; the result does not depend on it
  ProgressSink progress;
  /// When set: called with a PairSample before any pair of the matrix is computed; it may throw
  /// to refuse the work.
  std::function<void(const PairSample&)> before_pairs;
};

struct ViewFactorCounters {
  std::uint64_t patch_pairs = 0;             ///< unordered pairs of patches that both have a unit
  std::uint64_t skipped_pairs = 0;           ///< of those, dropped below the threshold (no shaft test)
  std::uint64_t dropped_by_closed_form = 0;  ///< of those, by the closed form (the rest by the cheap bound)
  std::uint64_t shaft_skipped = 0;  ///< below sample_below: sampled against the whole scene (counted in partial)
  std::uint64_t facing_away = 0;    ///< culled: exactly 0 without a kernel call
  std::uint64_t fully_visible = 0, fully_hidden = 0, partial = 0;
  std::uint64_t closed_forms = 0;  ///< polygon_to_polygon() calls
  std::uint64_t rays = 0;          ///< segments cast for partly visible pairs
  double classify_seconds = 0.0;   ///< classification and closed forms (with row_error: before sampling)
  std::uint64_t regions = 0;       ///< exact visible regions computed
  std::uint64_t capped_rows = 0;   ///< rows whose estimated sum exceeded 1, scaled down to 1 (row cap)
  double seconds = 0.0;
};

/// A square sparse matrix in compressed rows: the exchange areas E_uv = A_u F_uv (E symmetric, each
/// value stored in both rows, bit-identical) and the areas.
struct ViewFactorMatrix {
  int n = 0;
  std::vector<double> area;
  std::vector<std::int64_t> row_begin;  ///< n + 1 offsets into column / exchange
  std::vector<int> column;              ///< sorted within each row
  std::vector<double> exchange;         ///< E_uv
  std::vector<double> sampling_error;   ///< standard error of each row sum from sampled visibility
  std::vector<double> skipped_bound;    ///< bound of the factor mass in each row's skipped pairs
  std::vector<double> capped;           ///< factor each row lost to the row cap (0 in most rows)
  ViewFactorCounters counters;

  double factor(int u, std::int64_t k) const {
    return exchange[static_cast<std::size_t>(k)] / area[static_cast<std::size_t>(u)];
  }
  /// F_uv (0 when not stored).
  double factor(int u, int v) const;
  double row_sum(int u) const;
  std::size_t nonzeros() const { return column.size(); }
  /// Memory held by the matrix.
  std::size_t bytes() const;
};

/// Computes the matrix between `units` of `scene` (hrad::Error for a unit of zero area).
ViewFactorMatrix compute_view_factors(const Scene& scene, const SurfaceUnits& units, const ViewFactorOptions& options);

/// Largest |A_u F_uv - A_v F_vu| / A_u over stored entries, from the factors as stored.
double max_reciprocity_error(const ViewFactorMatrix& m);

}  // namespace hrad
