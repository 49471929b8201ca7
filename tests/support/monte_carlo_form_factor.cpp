#include "support/monte_carlo_form_factor.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

// Crossing-number test in the polygon's plane (Shimrat 1962; Haines 1994).
bool inside(const Vec2& p, const std::vector<Vec2>& poly) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 &a = poly[i], &b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

}  // namespace

MonteCarloFormFactor monte_carlo_form_factor(std::span<const Vec3> from, std::span<const Vec3> to,
                                             std::uint64_t samples, std::uint64_t seed) {
  MonteCarloFormFactor result;
  if (from.size() < 3 || to.size() < 3 || samples == 0) return result;
  const Vec3 o = from[0];
  const double scale = std::max(polygon_diameter(from), 1e-300);
  std::vector<Vec3> f, t;
  for (const Vec3& v : from) f.push_back((v - o) / scale);
  for (const Vec3& v : to) t.push_back((v - o) / scale);
  const Vec3 nf = newell_normal(f).normalized(), nt = newell_normal(t).normalized();
  const auto [u, v] = plane_basis(nf);
  const auto [tu, tv] = plane_basis(nt);
  std::vector<Vec2> t2;
  for (const Vec3& x : t) t2.emplace_back((x - t[0]).dot(tu), (x - t[0]).dot(tv));
  // Triangles of `from`, picked in proportion to their area.
  const auto tris = triangulate(f, nf);
  std::vector<double> cdf;
  double acc = 0.0;
  for (const auto& tri : tris) {
    acc += 0.5 * (f[tri[1]] - f[tri[0]]).cross(f[tri[2]] - f[tri[0]]).norm();
    cdf.push_back(acc);
  }
  if (!(acc > 0.0)) return result;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::uint64_t hits = 0;
  for (std::uint64_t s = 0; s < samples; ++s) {
    const double pick = uniform(rng) * acc;
    const std::size_t k =
        std::min<std::size_t>(std::lower_bound(cdf.begin(), cdf.end(), pick) - cdf.begin(), tris.size() - 1);
    double r1 = uniform(rng), r2 = uniform(rng);
    if (r1 + r2 > 1.0) r1 = 1.0 - r1, r2 = 1.0 - r2;
    const Vec3& a = f[tris[k][0]];
    const Vec3 x = a + r1 * (f[tris[k][1]] - a) + r2 * (f[tris[k][2]] - a);
    const double radius = std::sqrt(uniform(rng)), phi = 2.0 * std::numbers::pi * uniform(rng);
    const double dx = radius * std::cos(phi), dy = radius * std::sin(phi);
    const Vec3 d = dx * u + dy * v + std::sqrt(std::max(0.0, 1.0 - dx * dx - dy * dy)) * nf;
    const double facing = nt.dot(d);
    if (!(facing < 0.0)) continue;  // would reach to's back (or run parallel to it)
    const double dist = nt.dot(t[0] - x) / facing;
    if (!(dist > 0.0)) continue;
    const Vec3 hit = x + dist * d - t[0];
    if (inside(Vec2(hit.dot(tu), hit.dot(tv)), t2)) ++hits;
  }
  result.value = double(hits) / double(samples);
  result.standard_error = std::sqrt(result.value * (1.0 - result.value) / double(samples));
  return result;
}

}  // namespace hrad
