#include "hrad/solvers/closed_scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include <tbb/parallel_for.h>

#include "hrad/core/rng.h"
#include "hrad/geometry/polygon.h"
#include "hrad/visibility/sampling.h"

namespace hrad {

ClosureTestPlan closure_test_plan(double leaving, double emitted) {
  double ratio = emitted > 0.0 ? leaving / emitted : 1.0;
  if (!(std::isfinite(ratio) && ratio > 0.0)) ratio = 1.0;
  const double wanted = kClosureTestRaysPerLeavingPower * ratio;
  ClosureTestPlan plan;
  plan.rays = wanted > static_cast<double>(kLeastClosureTestRays)
                  ? std::min(kMostClosureTestRays, static_cast<std::uint64_t>(std::ceil(wanted)))
                  : kLeastClosureTestRays;
  plan.allowed_lost = static_cast<std::uint64_t>(std::floor(kClosureLoss * static_cast<double>(plan.rays) / ratio));
  return plan;
}

LightLoss light_loss(const Scene& scene, const ElementHierarchy& h, std::span<const Rgb> radiosity,
                     const Visibility& visibility, const ClosureTestPlan& plan, std::uint64_t seed) {
  LightLoss out;
  out.allowed_lost = plan.allowed_lost;
  const std::uint64_t rays = plan.rays;
  const std::vector<NodeId> leaves = h.all_leaves();
  std::vector<double> cdf;
  cdf.reserve(leaves.size());
  double total = 0.0;
  for (const NodeId leaf : leaves) {
    const double b = radiosity[static_cast<std::size_t>(leaf)].sum();
    total += h.node(leaf).area * std::max(0.0, b);
    cdf.push_back(total);
  }
  if (!(total > 0.0) || !std::isfinite(total)) return out;
  constexpr std::uint64_t kBatch = 4096;
  while (out.rays < rays && out.lost <= out.allowed_lost) {
    const std::uint64_t first = out.rays, count = std::min(kBatch, rays - out.rays);
    std::atomic<std::uint64_t> lost{0};
    tbb::parallel_for(tbb::blocked_range<std::uint64_t>(first, first + count, 256),
                      [&](const tbb::blocked_range<std::uint64_t>& range) {
                        for (std::uint64_t k = range.begin(); k != range.end(); ++k) {
                          detail::Rng rng(detail::mix_seed(seed, k));
                          const double pick = rng.uniform() * total;
                          const std::size_t i = std::min<std::size_t>(
                              static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), pick) - cdf.begin()),
                              leaves.size() - 1);
                          const ElementNode& leaf = h.node(leaves[i]);
                          const double u = rng.uniform(), v = rng.uniform();
                          const Vec3 x = detail::polygon_point(leaf.polygon(), u, v);
                          // A cosine-distributed direction about the patch's normal (Malley's method).
                          const Vec3& n = scene.patches[static_cast<std::size_t>(leaf.patch)].normal;
                          const auto [t, s] = plane_basis(n);
                          const double r2 = rng.uniform(), phi = 2.0 * std::numbers::pi * rng.uniform();
                          const double r = std::sqrt(r2);
                          const Vec3 d =
                              (r * std::cos(phi) * t + r * std::sin(phi) * s + std::sqrt(1.0 - r2) * n).normalized();
                          const RayHit hit = visibility.first_hit(x, leaf.patch, d);
                          if (hit.patch < 0 || !hit.front) lost.fetch_add(1, std::memory_order_relaxed);
                        }
                      });
    out.rays += count;
    out.lost += lost.load();
  }
  return out;
}

LightLoss test_light_loss(const Scene& scene, const ElementHierarchy& h, std::span<const Rgb> radiosity,
                          const Visibility* visibility, std::uint64_t seed) {
  double leaving = 0.0, emitted = 0.0;
  for (const NodeId leaf : h.all_leaves())
    leaving += h.node(leaf).area * radiosity[static_cast<std::size_t>(leaf)].sum();
  for (const Patch& p : scene.patches) emitted += p.area * scene.material_of(p).emission.sum();
  const ClosureTestPlan plan = closure_test_plan(leaving, emitted);
  if (visibility != nullptr) return light_loss(scene, h, radiosity, *visibility, plan, seed);
  const std::unique_ptr<Visibility> own = make_visibility(scene);
  LightLoss loss = light_loss(scene, h, radiosity, *own, plan, seed);
  loss.own_visibility = true;
  return loss;
}

}  // namespace hrad
