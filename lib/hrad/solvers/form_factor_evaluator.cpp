#include "hrad/solvers/form_factor_evaluator.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <vector>
#include <cassert>

#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/formfactor/receiver_gauss_factor.h"
#include "hrad/geometry/polygon.h"
#include "hrad/visibility/sampling.h"
#include "hrad/visibility/visibility.h"

namespace hrad {
namespace {

// True when every vertex of `b` lies on or behind the plane of `a` (front = Newell normal): the
// factor between them is then exactly 0 (only fronts emit and receive).
bool behind(std::span<const Vec3> a, std::span<const Vec3> b) {
  const Vec3 n = newell_normal(a);
  for (const Vec3& v : b)
    if ((v - a[0]).dot(n) > 0.0) return false;
  return true;
}

// Deterministic seed from the pair's geometry (splitmix-style mixing), so that a pair gets the same
// visibility samples whichever thread asks and in whichever order. Vertices enter relative to their
// patch's first vertex and diameter, quantized, so that a scaled scene draws the same samples.
std::uint64_t pair_seed(const Scene& scene, std::span<const Vec3> a, int pa, std::span<const Vec3> b, int pb) {
  std::uint64_t h = 0x9E3779B97F4A7C15ull ^ (static_cast<std::uint64_t>(pa) << 32) ^ static_cast<std::uint32_t>(pb);
  auto mix = [&h](std::uint64_t x) {
    h ^= x + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
    h ^= h >> 31;
  };
  auto add = [&](std::span<const Vec3> poly, int patch) {
    const Patch& p = scene.patches[static_cast<std::size_t>(patch)];
    const double size = polygon_diameter(p.vertices);
    for (const Vec3& v : poly)
      for (int k = 0; k < 3; ++k)
        mix(static_cast<std::uint64_t>(std::llround((v[k] - p.vertices[0][k]) / size * 0x1p30)));
  };
  add(a, pa);
  add(b, pb);
  return h;
}


}  // namespace

FormFactorEvaluator::FormFactorEvaluator(const Scene& scene, const Effects& effects, const Visibility* visibility,
                                         int visibility_samples, FormFactorKernel kernel)
    : scene_(scene),
      effects_(effects),
      visibility_(visibility),
      visibility_samples_(visibility_samples),
      kernel_(kernel) {
  assert(visibility_ != nullptr || !effects_.visibility);
  assert(visibility_samples_ > 0);
}

FormFactorEstimate FormFactorEvaluator::estimate(std::span<const Vec3> receiver, int receiver_patch,
                                                 std::span<const Vec3> source, int source_patch) const {
  FormFactorEstimate e;
  // Two elements of one planar patch never exchange light.
  if (receiver_patch == source_patch) return e;
  if (effects_.cull_facing_away && (behind(receiver, source) || behind(source, receiver))) {
    culled_.fetch_add(1, std::memory_order_relaxed);
    e.facing_away = true;
    return e;
  }
  if (effects_.visibility) {
    // Classify first: a fully hidden pair needs no kernel call, a fully visible one no samples.
    const PairClass c = visibility_->classify(receiver, receiver_patch, source, source_patch);
    visibility_queries_.fetch_add(1, std::memory_order_relaxed);
    if (c == PairClass::kFacingAway) {
      e.facing_away = true;
      e.visibility = 0.0;
      return e;
    }
    if (c == PairClass::kFullyHidden) {
      e.visibility = 0.0;
      return e;
    }
    if (c == PairClass::kPartial) {
      const auto [fraction, error] = weighted_visibility(receiver, receiver_patch, source, source_patch);
      e.partial = true;
      e.visibility = fraction;
      e.error = error;
    }
    const PairFormFactor f = unoccluded(receiver, source);
    e.unoccluded = f.from_to;
    e.value = f.from_to * e.visibility;
    e.reverse = f.to_from * e.visibility;
    e.error *= f.from_to;
    return e;
  }
  const PairFormFactor f = unoccluded(receiver, source);
  e.unoccluded = e.value = f.from_to;
  e.reverse = f.to_from;
  return e;
}

std::pair<double, double> FormFactorEvaluator::weighted_visibility(std::span<const Vec3> receiver, int receiver_patch,
                                                                  std::span<const Vec3> source,
                                                                  int source_patch) const {
  // Ray-traced form factors (Wallace, Elmquist & Haines 1989): the visible fraction weighted by the
  // point-to-point kernel cos(theta_x) cos(theta_y) / r^2 over stratified point pairs, so that the
  // near parts of a pair count as much as they contribute to F. The kernel is symmetric, so the
  // fraction is the same in both directions and reciprocity is kept.
  const std::uint64_t seed = pair_seed(scene_, receiver, receiver_patch, source, source_patch);
  const int kx = std::max(1, static_cast<int>(std::lround(std::sqrt(double(visibility_samples_)))));
  const int ky = std::max(1, (visibility_samples_ + kx - 1) / kx);
  detail::Rng rx(detail::mix_seed(seed, 1)), ry(detail::mix_seed(seed, 2));
  thread_local std::vector<Vec2> ux, uy;
  detail::stratified_unit_square(kx, rx, &ux);
  detail::stratified_unit_square(ky, ry, &uy);
  const detail::PolygonSampler sx(receiver), sy(source);
  const Vec3 nx = newell_normal(receiver).normalized(), ny = newell_normal(source).normalized();
  double weight = 0.0, visible_weight = 0.0;
  int visible = 0, count = 0;
  for (const Vec2& a : ux) {
    const Vec3 x = sx.point(a.x(), a.y());
    for (const Vec2& b : uy) {
      const Vec3 y = sy.point(b.x(), b.y());
      const Vec3 d = y - x;
      const double k = detail::point_pair_kernel(nx, ny, d);
      const bool seen = !visibility_->segment_blocked(x, receiver_patch, y, source_patch);
      weight += k;
      visible_weight += seen ? k : 0.0;
      visible += seen ? 1 : 0;
      ++count;
    }
  }
  const double error = detail::fraction_error(visible, count);
  if (!(weight > 0.0)) return {count > 0 ? double(visible) / count : 1.0, error};
  return {visible_weight / weight, error};
}

PairFormFactor FormFactorEvaluator::unoccluded(std::span<const Vec3> receiver, std::span<const Vec3> source) const {
  evaluations_.fetch_add(1, std::memory_order_relaxed);
  if (kernel_ == FormFactorKernel::kAnalytic) return polygon_to_polygon(receiver, source, kSolverPairTolerance);
  return {receiver_gauss_factor(receiver, source), receiver_gauss_factor(source, receiver)};
}

}  // namespace hrad
