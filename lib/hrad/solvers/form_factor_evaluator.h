// The one place where a form-factor kernel and a visibility rule are chosen. Every solver (full
// matrix, substructuring, hierarchical) asks this class for the factor between two elements.
#pragma once

#include <atomic>
#include <cstdint>
#include <span>
#include <utility>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/solvers/effects.h"

namespace hrad {

class Visibility;

/// The accuracy the solvers ask of polygon_to_polygon(): far below any discretisation or visibility
/// error, and closure in a closed room still holds to ~1e-9, so B = E / (1 - rho) to ~1e-9 / (1 - rho)
/// (hard_test asserts 1e-3 at rho 0.999). With the kernel's default (1e-11 and full-precision Gauss
/// for far pairs) the Cornell box's hierarchical refinement at 1968 elements took 22.7 s instead of
/// 3.3 s (one thread; perf put 67% in the far-field quadrature).
inline constexpr double kSolverPairTolerance = 1e-9;

/// How the unoccluded factor of a pair is computed.
enum class FormFactorKernel {
  /// polygon_to_polygon(): the closed-form double contour integral (Schroeder & Hanrahan 1993),
  /// exact to ~1e-13 and exactly reciprocal; costlier (~5 us for quads in general position, ~1 us for parallel ones: formfactor_benchmark).
  kAnalytic,
  /// Fixed Gauss points on the receiver (3 x 3 on a quad, 12 on a triangle) and
  /// Lambert's exact contour formula from each point to the source (point_to_polygon(); Cohen &
  /// Wallace 1993, eq. 4.16): F(i -> j) = (1/A_i) sum_k w_k F(dA_k -> j). Each point's factors to a
  /// closed surface sum to exactly 1, so rows still sum to 1 in a closed room (closure) and the
  /// closed forms hold to rounding; reciprocity holds to the quadrature error. Several times faster (solvers_benchmark BM_KernelPairs).
  kPointContour,
};

struct FormFactorEstimate {
  double value = 0.0;       ///< F(receiver -> source) = unoccluded analytic factor * visibility fraction
  /// F(source -> receiver) with the same visibility fraction: reciprocal to rounding with kAnalytic;
  /// with kPointContour computed from Gauss points on the source (closure over reciprocity).
  double reverse = 0.0;
  double unoccluded = 0.0;  ///< F(receiver -> source) without occlusion (0 when fully hidden: not computed)
  double visibility = 1.0;  ///< visible fraction in [0, 1] (1 when visibility is off)
  /// Estimate of |value - true F(receiver -> source)|: unoccluded * visibility error (0 when the
  /// pair was classified exactly or visibility is off; the analytic kernel is exact to rounding).
  double error = 0.0;
  bool facing_away = false;  ///< culled without calling the kernel (value 0)
  /// Classified partly visible (visibility sampled), even when every sample was visible or hidden.
  bool partial = false;
};

/// Thread-safe: estimate() may be called from many threads; counters are atomic, and each call
/// is deterministic (the visibility sampling seed is derived from the pair's geometry).
class FormFactorEvaluator {
 public:
  /// `visibility` may be null only when `effects.visibility` is false. `visibility_samples` is the
  /// number of point pairs sampled for a partially visible pair (> 0).
  FormFactorEvaluator(const Scene& scene, const Effects& effects, const Visibility* visibility,
                      int visibility_samples, FormFactorKernel kernel = FormFactorKernel::kPointContour);

  /// Factor from `receiver` (a polygon lying on patch `receiver_patch`) to `source` (on
  /// `source_patch`). Polygons are counter-clockwise seen from their patches' fronts. Pairs on
  /// one patch are coplanar and give 0 without a kernel call; pairs facing away are culled when
  /// effects.cull_facing_away; the visibility oracle is asked only when effects.visibility.
  FormFactorEstimate estimate(std::span<const Vec3> receiver, int receiver_patch, std::span<const Vec3> source,
                              int source_patch) const;

  /// Kernel calls (polygon_to_polygon) so far; one call gives both directions.
  std::uint64_t evaluations() const { return evaluations_.load(std::memory_order_relaxed); }
  /// Visibility oracle calls (pair classifications and estimates) so far.
  std::uint64_t visibility_queries() const { return visibility_queries_.load(std::memory_order_relaxed); }
  /// Pairs culled as facing away so far.
  std::uint64_t culled_pairs() const { return culled_.load(std::memory_order_relaxed); }

  const Effects& effects() const { return effects_; }
  FormFactorKernel kernel() const { return kernel_; }

 private:
  // Both directions of the unoccluded factor with the chosen kernel; counts one evaluation.
  PairFormFactor unoccluded(std::span<const Vec3> receiver, std::span<const Vec3> source) const;
  // Kernel-weighted visible fraction of a partially visible pair and its error estimate.
  std::pair<double, double> weighted_visibility(std::span<const Vec3> receiver, int receiver_patch,
                                                std::span<const Vec3> source, int source_patch) const;

  const Scene& scene_;
  Effects effects_;
  const Visibility* visibility_;
  int visibility_samples_;
  FormFactorKernel kernel_;
  mutable std::atomic<std::uint64_t> evaluations_{0};
  mutable std::atomic<std::uint64_t> visibility_queries_{0};
  mutable std::atomic<std::uint64_t> culled_{0};
};

}  // namespace hrad
