#include "hrad/visibility/sampling.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hrad::detail {

PolygonSampler::PolygonSampler(std::span<const Vec3> polygon) : vertices_(polygon.begin(), polygon.end()) {
  const std::size_t k = vertices_.size();
  double sum = 0.0;
  for (std::size_t i = 1; i + 1 < k; ++i) {
    sum += 0.5 * (vertices_[i] - vertices_[0]).cross(vertices_[i + 1] - vertices_[0]).norm();
    cdf_.push_back(sum);
  }
  area_ = sum;
  if (sum > 0.0)
    for (double& c : cdf_) c /= sum;
  if (!cdf_.empty()) cdf_.back() = 1.0;
}

Vec3 PolygonSampler::point(double u, double v) const {
  if (cdf_.empty()) return vertices_.empty() ? Vec3::Zero() : vertices_[0];
  const std::size_t i = std::min<std::size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin(),
                                              cdf_.size() - 1);
  const double lo = i == 0 ? 0.0 : cdf_[i - 1];
  const double width = cdf_[i] - lo;
  const double uu = width > 0.0 ? std::clamp((u - lo) / width, 0.0, 1.0) : 0.0;
  const double su = std::sqrt(uu);
  const Vec3& v0 = vertices_[0];
  return v0 + (su * (1.0 - v)) * (vertices_[i + 1] - v0) + (su * v) * (vertices_[i + 2] - v0);
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
