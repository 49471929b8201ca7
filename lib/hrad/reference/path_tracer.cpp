#include "hrad/reference/path_tracer.h"

#include <cmath>
#include <numbers>
#include <numeric>

#include "hrad/geometry/polygon.h"

namespace hrad::detail {
namespace {

// Power heuristic with exponent 2 (Veach 1997, eq. 9.13): the weight of the strategy with density a.
double power_heuristic(double a, double b) {
  const double a2 = a * a, b2 = b * b;
  return a2 / (a2 + b2);
}

}  // namespace

// A direction with density cos(theta) / pi about n: a uniform point on the unit disc lifted to the
// hemisphere (Malley's method; Pharr, Jakob & Humphreys, "Physically Based Rendering", 4th ed., sec. A.5.3).
Vec3 cosine_direction(const Vec3& n, Rng& rng) {
  const double u = rng.uniform(), phi = 2 * std::numbers::pi * rng.uniform();
  const double r = std::sqrt(u);
  const auto [s, t] = plane_basis(n);
  return (r * std::cos(phi)) * s + (r * std::sin(phi)) * t + std::sqrt(std::max(0.0, 1.0 - u)) * n;
}

PathTracer::PathTracer(const EmbreeScene& rays, int max_depth, int roulette_depth)
    : rays_(rays), scene_(rays.scene()), max_depth_(max_depth), roulette_depth_(roulette_depth) {
  const std::size_t n = scene_.patches.size();
  reflectance_.resize(n);
  emission_.resize(n);
  std::vector<double> power_density(n, 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    const Material& m = scene_.material_of(scene_.patches[p]);
    reflectance_[p] = m.reflectance;
    emission_[p] = m.emission;
    power_density[p] = m.emission.sum();
  }
  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  emitters_ = AreaSampler(scene_, all, power_density);
}

Rgb PathTracer::irradiance(const Vec3& x0, const Vec3& n0, Rng& rng, RayCounts& counts) const {
  constexpr double kInvPi = 1.0 / std::numbers::pi;
  Rgb estimate = Rgb::Zero();
  Rgb throughput = Rgb::Ones();
  Vec3 x = x0, n = n0;
  // Vertex `depth` starts the segment number depth + 1.
  for (int depth = 0; max_depth_ == 0 || depth < max_depth_; ++depth) {
    if (!emitters_.empty()) {
      const double u = rng.uniform(), v = rng.uniform();
      const SurfacePoint light = emitters_.sample(u, v);
      const Vec3 d = light.point - x;
      const double r2 = d.squaredNorm();
      const double r = std::sqrt(r2);
      const auto k = static_cast<std::size_t>(light.patch);
      const double cos_x = n.dot(d) / r, cos_y = -scene_.patches[k].normal.dot(d) / r;
      if (cos_x > 0.0 && cos_y > 0.0 && !rays_.blocked(x, light.point, counts)) {
        const double p_light = emitters_.density(light.patch) * r2 / cos_y, p_bsdf = cos_x * kInvPi;
        // (E cos_x / pi) / p_light * w_light, written without dividing by a small density.
        estimate += throughput * emission_[k] * (p_bsdf * p_light / (p_light * p_light + p_bsdf * p_bsdf));
      }
    }

    const Vec3 w = cosine_direction(n, rng);
    const RayHit hit = rays_.closest_hit(x, w, counts);
    if (hit.patch < 0 || !hit.front) break;  // left the scene, or a black back
    const auto j = static_cast<std::size_t>(hit.patch);
    if (!emitters_.empty() && emitters_.density(hit.patch) > 0.0) {
      const Vec3 d = hit.point - x;
      const double r2 = d.squaredNorm();
      const double cos_y = -scene_.patches[j].normal.dot(w);
      const double p_light = emitters_.density(hit.patch) * r2 / cos_y, p_bsdf = n.dot(w) * kInvPi;
      estimate += throughput * emission_[j] * power_heuristic(p_bsdf, p_light);
    }

    const Rgb& rho = reflectance_[j];
    const double q = rho.maxCoeff();
    if (!(q > 0.0)) break;
    throughput *= rho;
    if (depth + 1 >= roulette_depth_) {
      if (rng.uniform() >= q) break;
      throughput /= q;
    }
    x = hit.point;
    n = scene_.patches[j].normal;
  }
  return estimate;
}

}  // namespace hrad::detail
