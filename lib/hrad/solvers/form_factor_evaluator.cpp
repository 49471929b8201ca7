#include "hrad/solvers/form_factor_evaluator.h"

#include <bit>
#include <cassert>

#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/geometry/polygon.h"
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

// Deterministic seed from the pair's geometry (splitmix-style mixing), so that a pair gets the
// same visibility samples whichever thread asks, and in whichever order.
std::uint64_t pair_seed(std::span<const Vec3> a, int pa, std::span<const Vec3> b, int pb) {
  std::uint64_t h = 0x9E3779B97F4A7C15ull ^ (static_cast<std::uint64_t>(pa) << 32) ^ static_cast<std::uint32_t>(pb);
  auto mix = [&h](std::uint64_t x) {
    h ^= x + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
    h ^= h >> 31;
  };
  for (const Vec3& v : a)
    for (int k = 0; k < 3; ++k) mix(std::bit_cast<std::uint64_t>(v[k]));
  for (const Vec3& v : b)
    for (int k = 0; k < 3; ++k) mix(std::bit_cast<std::uint64_t>(v[k]));
  return h;
}

}  // namespace

FormFactorEvaluator::FormFactorEvaluator(const Scene& scene, const Effects& effects, const Visibility* visibility,
                                         int visibility_samples)
    : scene_(scene), effects_(effects), visibility_(visibility), visibility_samples_(visibility_samples) {
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
    // Visibility first: a fully hidden pair needs no kernel call.
    const VisibilityEstimate v =
        visibility_->estimate(receiver, receiver_patch, source, source_patch, visibility_samples_,
                              pair_seed(receiver, receiver_patch, source, source_patch));
    visibility_queries_.fetch_add(1, std::memory_order_relaxed);
    e.visibility = v.fraction;
    if (v.pair_class == PairClass::kFacingAway) {
      e.facing_away = true;
      e.visibility = 0.0;
      return e;
    }
    if (v.fraction == 0.0 && v.pair_class == PairClass::kFullyHidden) return e;
    const PairFormFactor f = polygon_to_polygon(receiver, source);
    evaluations_.fetch_add(1, std::memory_order_relaxed);
    e.unoccluded = f.from_to;
    e.value = f.from_to * v.fraction;
    e.reverse = f.to_from * v.fraction;
    e.error = f.from_to * v.error;
    return e;
  }
  const PairFormFactor f = polygon_to_polygon(receiver, source);
  evaluations_.fetch_add(1, std::memory_order_relaxed);
  e.unoccluded = e.value = f.from_to;
  e.reverse = f.to_from;
  return e;
}

}  // namespace hrad
