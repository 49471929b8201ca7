#include "hrad/visibility/sampling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace hrad::detail {

namespace {

// The fan from vertex 0's cumulative triangle areas into cdf[0 .. k - 3], normalised, the last set
// to 1; returns the polygon's area.
double fan_cdf(std::span<const Vec3> p, double* cdf) {
  const std::size_t k = p.size();
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < k; ++i) {
    sum += 0.5 * (p[i] - p[0]).cross(p[i + 1] - p[0]).norm();
    cdf[i - 1] = sum;
  }
  if (k < 3) return sum;
  if (sum > 0.0)
    for (std::size_t i = 0; i + 2 < k; ++i) cdf[i] /= sum;
  cdf[k - 3] = 1.0;
  return sum;
}

// The point of the fan from vertex 0 at (u, v): u picks the triangle by its cumulative share `cdf`
// (normalised, the last 1) and is remapped into it; the square-root warp (Turk 1990).
Vec3 fan_point(std::span<const Vec3> vertices, std::span<const double> cdf, double u, double v) {
  const std::size_t i =
      std::min<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin(), cdf.size() - 1);
  const double lo = i == 0 ? 0.0 : cdf[i - 1];
  const double width = cdf[i] - lo;
  const double uu = width > 0.0 ? std::clamp((u - lo) / width, 0.0, 1.0) : 0.0;
  const double su = std::sqrt(uu);
  const Vec3& v0 = vertices[0];
  return v0 + (su * (1.0 - v)) * (vertices[i + 1] - v0) + (su * v) * (vertices[i + 2] - v0);
}

}  // namespace

PolygonSampler::PolygonSampler(std::span<const Vec3> polygon)
    : vertices_(polygon.begin(), polygon.end()), cdf_(polygon.size() >= 3 ? polygon.size() - 2 : 0) {
  area_ = fan_cdf(std::span<const Vec3>(vertices_.data(), vertices_.size()), cdf_.data());
}

Vec3 PolygonSampler::point(double u, double v) const {
  if (cdf_.empty()) return vertices_.empty() ? Vec3::Zero() : vertices_[0];
  return fan_point(std::span<const Vec3>(vertices_.data(), vertices_.size()),
                   std::span<const double>(cdf_.data(), cdf_.size()), u, v);
}

Vec3 polygon_point(std::span<const Vec3> polygon, double u, double v) {
  constexpr std::size_t kMax = 16;
  const std::size_t k = polygon.size();
  if (k > kMax) return PolygonSampler(polygon).point(u, v);
  if (k < 3) return polygon.empty() ? Vec3::Zero() : polygon[0];
  // The sampler's arithmetic, step for step, on the stack.
  std::array<double, kMax> cdf;
  fan_cdf(polygon, cdf.data());
  const std::size_t triangles = k - 2;
  return fan_point(polygon, std::span<const double>(cdf.data(), triangles), u, v);
}

void stratified_unit_square(int n, Rng& rng, std::vector<Vec2>* out) {
  out->clear();
  if (n <= 0) return;
  const int m = static_cast<int>(std::ceil(std::sqrt(double(n))));
  std::vector<int> cells(static_cast<std::size_t>(m) * m);
  std::iota(cells.begin(), cells.end(), 0);
  // Partial Fisher-Yates: the first n cells are a uniform random n-subset in random order.
  for (int i = 0; i < n; ++i) {
    const std::size_t j = i + rng.below(cells.size() - i);
    std::swap(cells[i], cells[j]);
  }
  out->reserve(n);
  for (int i = 0; i < n; ++i) {
    const int cx = cells[i] % m, cy = cells[i] / m;
    out->emplace_back((cx + rng.uniform()) / m, (cy + rng.uniform()) / m);
  }
}

double fraction_error(int visible, int n) {
  if (n <= 0) return 1.0;
  const double p = double(visible) / n, z = 1.0;
  return z / (1.0 + z * z / n) * std::sqrt(p * (1.0 - p) / n + z * z / (4.0 * n * n));
}

}  // namespace hrad::detail
