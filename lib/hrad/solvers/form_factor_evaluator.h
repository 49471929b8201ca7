// The one place where a form-factor kernel and a visibility rule are chosen. Every solver (full
// matrix, substructuring, hierarchical) asks this class for the factor between two elements.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/formfactor/receiver_gauss_factor.h"
#include "hrad/solvers/effects.h"
#include "hrad/solvers/work.h"
#include "hrad/visibility/visibility.h"

namespace hrad {

/// The accuracy the solvers ask of polygon_to_polygon(): far below any discretisation or visibility
/// error, and closure in a closed room still holds to ~1e-9, so B = E / (1 - rho) to ~1e-9 / (1 - rho)
/// (hard_test asserts 1e-3 at rho 0.999). The kernel's default (1e-11, full-precision Gauss for far
/// pairs) spends most of a hierarchical refinement in the far-field quadrature;
/// tests/bench/hierarchical_benchmark.cpp measures the refinement.
inline constexpr double kSolverPairTolerance = 1e-9;

/// How the unoccluded factor of a pair is computed.
enum class FormFactorKernel {
  /// polygon_to_polygon(): the closed-form double contour integral (Schroeder & Hanrahan 1993),
  /// exact to ~1e-13 and exactly reciprocal; costlier (~5 us for quads in general position, ~1 us for parallel ones:
  /// formfactor_benchmark).
  kAnalytic,
  /// Fixed Gauss points on the receiver (3 x 3 on a quad, 12 on a triangle) and
  /// Lambert's exact contour formula from each point to the source (point_to_polygon(); Cohen &
  /// Wallace 1993, eq. 4.16): F(i -> j) = (1/A_i) sum_k w_k F(dA_k -> j). Each point's factors to a
  /// closed surface sum to exactly 1, so rows still sum to 1 in a closed room (closure) and the
  /// closed forms hold to rounding; reciprocity holds to the quadrature error. Several times faster (solvers_benchmark
  /// BM_KernelPairs). A receiver's cells are graded towards the edges of patches that float close in
  /// front of it (no vertex touching its plane: a lamp a millimetre from a wall), where a cell
  /// larger than their distance cannot follow the factor's rise; the points still do not depend on
  /// the source, so closure holds.
  kPointContour,
};

struct FormFactorEstimate {
  double value = 0.0;  ///< F(receiver -> source) = unoccluded analytic factor * visibility fraction
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

/// The surfaces below a node of the clustered hierarchy (an element or a cluster), for the sampled
/// factor between two nodes.
class SurfaceSampler {
 public:
  virtual ~SurfaceSampler() = default;
  virtual double area() const = 0;
  /// A point uniform by area on the surfaces from three numbers in [0, 1); returns its patch.
  virtual int sample(double w, double u, double v, Vec3* point) const = 0;
  /// The number of patches below the node (1 for an element).
  virtual int patch_count() const = 0;
  /// A point uniform by area on the node's k-th patch (on the element itself for an element) from
  /// two numbers in [0, 1); returns that patch.
  virtual int sample_patch(int k, double u, double v, Vec3* point) const = 0;
};

/// A patch at one end of a cluster link, as seen from it along rays to the other end: the
/// kernel-weighted fraction of the other end it sees (0: nothing) and its sampled factor to the
/// other end, visibility included (FormFactorEvaluator::shaded_surfaces()). Lists of them are sorted
/// by patch; a patch not listed sees all of the other end and sends nothing through the link.
struct ShadedPatch {
  int patch = -1;
  float visible = 0.0f;
  float factor = 0.0f;
  bool operator<(const ShadedPatch& o) const { return patch < o.patch; }
};
using ShadedPatches = std::vector<ShadedPatch>;

/// The visible fraction of `patch` in `shaded` (null: none listed): 1 when not listed.
inline double visible_share(const ShadedPatches* shaded, int patch) {
  if (shaded == nullptr) return 1.0;
  const auto it = std::lower_bound(shaded->begin(), shaded->end(), ShadedPatch{patch, 0.0f});
  return it != shaded->end() && it->patch == patch ? static_cast<double>(it->visible) : 1.0;
}

/// Kernel-weighted visibility of a polygon from a point (Wallace, Elmquist & Haines 1989): sums over
/// the rays of the point-to-point kernel cos(theta_x) cos(theta_y) / r^2, and of it where the ray is
/// not blocked. visible / weight is the visible fraction of the point's factor to the polygon.
struct KernelVisibility {
  double visible = 0.0;
  double weight = 0.0;
  int visible_rays = 0;
  int rays = 0;  ///< rays that carry weight (both points in front of each other)
};

/// One point pair of FormFactorEvaluator::pair_visibility() that carried weight: its points on the
/// receiver (x) and the source (y), its kernel weight and its outcome.
struct VisibilityPair {
  Vec3 x, y;
  double weight = 0.0;
  bool visible = false;
};

/// A partly visible pair's kernel-weighted visible fraction (FormFactorEvaluator::pair_visibility())
/// from n point pairs with kernel weights w_i and outcomes V_i (1: unblocked).
struct PairVisibility {
  /// The ratio sum w V / sum w: in [0, 1], but biased by O(1 / n) where w and V correlate (near
  /// parts that see each other, far parts shaded; Cochran 1977, Sampling techniques, ch. 6); 0 when
  /// no ray passed.
  double fraction = 0.0;
  double error = 0.0;    ///< detail::fraction_error() of the rays' outcomes
  int rays = 0;          ///< point pairs that carried weight
  int visible_rays = 0;  ///< of which unblocked
  /// E[w] per unit of the pair's unoccluded exchange A F: pi / A'x (near pairs) or pi / (A'x A'y).
  double mean_weight_per_exchange = 0.0;
  /// sum w V, sum w and n of each of two independent halves of the pairs (halves[1].pairs = 0:
  /// drawn as one set).
  struct Half {
    double visible = 0.0, weight = 0.0;
    int pairs = 0;
  };
  std::array<Half, 2> halves{};

  /// sum w V over all the pairs.
  double visible() const { return halves[0].visible + halves[1].visible; }

  /// The control-variate estimate (sum w V - c (sum w - n W)) / (n W), W = E[w] from the pair's
  /// exact unoccluded exchange: unbiased for any coefficient c independent of the pairs it is
  /// applied to (Owen 2013, Monte Carlo theory, methods and examples, ch. 8). Drawn as two
  /// independent halves, each half takes the other's ratio as c (cross-fitting), which is about the
  /// fraction, so the estimate is about as precise as the ratio; `coefficient` (an estimate
  /// independent of these pairs) serves where a half carries no weight or there are no halves. It
  /// may stray outside [0, 1] by its noise. 0 when no ray passed, as `fraction`: nothing seen is
  /// linked.
  double controlled(double exchange, double coefficient) const {
    if (!(visible() > 0.0) || !(exchange > 0.0) || !(mean_weight_per_exchange > 0.0)) return fraction;
    const double w = mean_weight_per_exchange * exchange;
    if (halves[1].pairs == 0) {
      const Half& all = halves[0];
      return (all.visible - coefficient * (all.weight - all.pairs * w)) / (all.pairs * w);
    }
    double sum = 0.0;
    for (int k = 0; k < 2; ++k) {
      const Half& self = halves[static_cast<std::size_t>(k)];
      const Half& other = halves[static_cast<std::size_t>(1 - k)];
      const double c = other.weight > 0.0 ? other.visible / other.weight : coefficient;
      sum += self.visible - c * (self.weight - self.pairs * w);
    }
    return sum / ((halves[0].pairs + halves[1].pairs) * w);
  }
};

/// Heights over a polygon's plane below this fraction of its diameter are contact (rounding of
/// touching vertices), not floating.
inline constexpr double kContactTolerance = 1e-9;

/// Thread-safe: every method may be called from many threads; counters are per thread
/// (work_counter.h), and each call is deterministic (sampling seeds come from the pair's geometry
/// or the caller).
class FormFactorEvaluator {
 public:
  /// `visibility` may be null only when `effects.visibility` is false. `visibility_samples` is the
  /// number of point pairs sampled for a partially visible pair (> 0).
  FormFactorEvaluator(const Scene& scene, const Effects& effects, const Visibility* visibility, int visibility_samples,
                      FormFactorKernel kernel = FormFactorKernel::kPointContour, std::uint64_t seed = 0);

  /// The polygons the factors will be taken to (the solver's elements or shooting patches), each
  /// on its patch: the contour rule grades a receiver's points towards their edges where their
  /// patch floats close in front of the receiver's, so that all of one receiver's factors share one
  /// point set (closure) and each follows its source's near field. Call before the first factor
  /// (later, std::logic_error); without it, the patches' own edges.
  void set_sources(std::span<const std::span<const Vec3>> polygons, std::span<const int> patches);

  /// Factor from `receiver` (a polygon lying on patch `receiver_patch`) to `source` (on
  /// `source_patch`). Polygons are counter-clockwise seen from their patches' fronts. Pairs on
  /// one patch are coplanar and give 0 without a kernel call; pairs facing away are culled when
  /// effects.cull_facing_away; the visibility oracle is asked only when effects.visibility.
  /// `with_reverse` false: the contour kernel skips the source's points and `reverse` is 0 (a
  /// solver that gathers in one direction only).
  FormFactorEstimate estimate(std::span<const Vec3> receiver, int receiver_patch, std::span<const Vec3> source,
                              int source_patch, bool with_reverse = true) const;

  /// True (and counted as culled) when the effects cull facing-away pairs and one polygon lies
  /// wholly on or behind the other's plane: their factor is exactly 0.
  bool faces_away(std::span<const Vec3> a, std::span<const Vec3> b) const;

  /// F(dA_x -> source), unoccluded, for a point x with unit normal n (point_to_polygon()).
  double point_factor(const Vec3& x, const Vec3& n, std::span<const Vec3> source) const;
  /// The same approached from inside x's element along `inward` (point_to_polygon_limit()): the
  /// factor's one-sided limit where x lies in the source's plane, e.g. on a shared edge. Both are
  /// plain Lambert sums (kLambertSumOnly: ~1e-16 absolute, no refinement where the sum cancels).
  double point_factor(const Vec3& x, const Vec3& n, const Vec3& inward, std::span<const Vec3> source) const;

  /// Both directions of the unoccluded factor by the closed form (polygon_to_polygon() at
  /// `rel_tol`, or `abs_tol` in factor units), whatever the evaluator's kernel.
  PairFormFactor analytic(std::span<const Vec3> receiver, std::span<const Vec3> source,
                          double rel_tol = kSolverPairTolerance, double abs_tol = 0.0) const;

  /// Both directions by Gauss points on each polygon (receiver_gauss_factor(): 3 x 3 on a quad,
  /// degree 5) with the exact point factor at each, made reciprocal by taking the mean of the two
  /// exchanges A F. For polygons small against their distance the rule's error falls like
  /// (size / distance)^6: ~1e-8 relative at a quarter (formfactor_test ReceiverGaussFactor).
  PairFormFactor gauss(std::span<const Vec3> receiver, std::span<const Vec3> source) const;

  /// F(receiver -> source) by receiver_factor_by_distance(): one point where the receiver is small
  /// against its distance to the source (diameter <= centroid_ratio x gap), Gauss points otherwise.
  double receiver_factor(std::span<const Vec3> receiver, std::span<const Vec3> source, double centroid_ratio) const;

  /// Visibility::classify_among() (see there); kFullyVisible without a query when the effects
  /// need no visibility.
  PairClass classify(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b,
                     const std::vector<int>* candidates, std::vector<int>* occluders) const;

  /// Kernel-weighted visibility of `source` from the point x (unit normal nx, on patch_x) by `rays`
  /// stratified points of the source (deterministic in `seed`); only the patches `occluders` can
  /// block when it is not null (a pair's occluders from classify()).
  KernelVisibility visibility_from_point(const Vec3& x, const Vec3& nx, int patch_x, std::span<const Vec3> source,
                                         int source_patch, const std::vector<int>* occluders, int rays,
                                         std::uint64_t seed) const;

  /// Kernel-weighted visible fraction of a partly visible pair from `samples` point pairs (0: the
  /// evaluator's number), stratified on both polygons (Wallace, Elmquist & Haines 1989),
  /// deterministic in the pair's geometry and `stream`: another stream draws point pairs independent
  /// of stream 0's (a link's factor must not come from the samples that decided to keep it); only
  /// `occluders` can block when not null.
  /// With `halves`, the pairs are drawn as two independent stratified halves
  /// (PairVisibility::controlled()). `pairs`, when given, receives the pairs that carried weight.
  PairVisibility pair_visibility(std::span<const Vec3> receiver, int receiver_patch, std::span<const Vec3> source,
                                 int source_patch, const std::vector<int>* occluders = nullptr, int samples = 0,
                                 std::uint64_t stream = 0, bool halves = false,
                                 std::vector<VisibilityPair>* pairs = nullptr) const;

  /// Factor between the surfaces of two nodes by `samples` stratified point pairs (uniform by area
  /// on each side): F(p -> q) = A_q mean(cos cos V / (pi r^2)), the visibility V by rays through the
  /// whole scene. Unbiased, reciprocal by construction; `error` is its standard error. value
  /// F(p -> q), reverse F(q -> p), visibility the kernel-weighted visible fraction.
  /// `seen_p` and `seen_q`, when given, receive the patches of each side that some visible sample
  /// pair joined (in sample order, with repeats).
  FormFactorEstimate sampled(const SurfaceSampler& p, const SurfaceSampler& q, int samples, std::uint64_t seed,
                             std::vector<int>* seen_p = nullptr, std::vector<int>* seen_q = nullptr) const;

  /// Every patch of `from`, along `rays` rays from points uniform on the patch to points uniform by
  /// area on `to`, visibility decided exactly (Visibility::sight()): the kernel-weighted visible
  /// fraction sum k V / sum k (k the point pair kernel; 0 when no ray carries weight) and the factor
  /// A_to sum k V / (pi rays), an unbiased estimate of F(patch -> to); sorted. A patch behind a
  /// closed surface never sees through it, whatever the rays: a cluster link must give it nothing;
  /// a patch half hidden by furniture inside its own cluster must get half of an unobstructed
  /// patch's share (hsa_links.h). `reached`, when given, gets the patch of `to` at the far end of
  /// every ray that passed.
  ShadedPatches shaded_surfaces(const SurfaceSampler& from, const SurfaceSampler& to, int rays, std::uint64_t seed,
                                std::vector<int>* reached = nullptr) const;

  /// Deterministic seed for sampling a pair of polygons on patches pa and pb (from their geometry,
  /// relative to their patches: a scaled scene draws the same samples), mixed with the stream's
  /// seed (SolveOptions::seed) when it is not 0.
  std::uint64_t pair_seed(std::span<const Vec3> a, int pa, std::span<const Vec3> b, int pb) const;
  /// A seed of the caller's own mixed with the stream's seed when it is not 0.
  std::uint64_t stream_seed(std::uint64_t seed) const;

  /// Counters so far (segment queries from the visibility oracle, which counts every ray).
  Work work() const;
  /// Kernel calls (analytic, Gauss-point and sampled element factors) so far.
  std::uint64_t evaluations() const { return evaluations_.load(); }
  /// Shaft classifications so far.
  std::uint64_t visibility_queries() const { return shaft_queries_.load(); }
  /// Pairs culled as facing away so far.
  std::uint64_t culled_pairs() const { return culled_.load(); }

  const Effects& effects() const { return effects_; }
  FormFactorKernel kernel() const { return kernel_; }
  int visibility_samples() const { return visibility_samples_; }
  const Scene& scene() const { return scene_; }

  /// True when the receiver's diameter is at most `ratio` times the gap between the two polygons'
  /// bounding spheres (about their vertex means).
  static bool separated(std::span<const Vec3> receiver, std::span<const Vec3> source, double ratio);

 private:
  // Both directions of the unoccluded factor with the chosen kernel; counts one evaluation.
  PairFormFactor unoccluded(std::span<const Vec3> receiver, int receiver_patch, std::span<const Vec3> source,
                            int source_patch, bool with_reverse) const;
  // F(receiver -> source) by the contour rule on the receiver's points, graded towards the edges of
  // the patches that float close in front of it and the edges emitters have in its plane
  // (receiver_gauss_points(), kCreaseDepth).
  double contour_factor(std::span<const Vec3> receiver, int receiver_patch, std::span<const Vec3> source,
                        int* points) const;
  // The edges of the sources on patches floating in front of `patch`, and of the emitters' sources
  // lying in its plane, found once.
  const std::vector<NearEdge>& floating_edges(int patch) const;
  const Scene& scene_;
  Effects effects_;
  const Visibility* visibility_;
  int visibility_samples_;
  FormFactorKernel kernel_;
  std::uint64_t seed_;
  mutable WorkCounter evaluations_;
  mutable WorkCounter point_factors_;
  mutable WorkCounter shaft_queries_;
  mutable WorkCounter culled_;
  mutable std::once_flag floating_once_;
  mutable std::atomic<bool> floating_built_{false};  ///< set_sources() is refused from then on
  mutable std::vector<std::vector<std::vector<Vec3>>> sources_by_patch_;
  mutable std::vector<std::vector<NearEdge>> floating_edges_;
};

}  // namespace hrad
