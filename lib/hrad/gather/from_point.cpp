#include "hrad/gather/from_point.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "hrad/core/rng.h"
#include "hrad/visibility/sampling.h"

namespace hrad::detail {
namespace {

std::uint64_t bits_of(double v) {
  std::uint64_t b = 0;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

}  // namespace

std::uint64_t point_seed(const GatherPoint& p, std::uint64_t seed) {
  std::uint64_t h = mix_seed(seed, 0x5eed);
  for (int c = 0; c < 3; ++c) {
    h = mix_seed(h, bits_of(p.position[c]));
    h = mix_seed(h, bits_of(p.normal[c]));
  }
  return h;
}

std::pair<double, double> kernel_bounds(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon, double h) {
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : polygon) centre += v;
  centre /= static_cast<double>(polygon.size());
  double radius = 0.0, r_max = 0.0, s_min = INFINITY, s_max = -INFINITY;
  for (const Vec3& v : polygon) {
    radius = std::max(radius, (v - centre).norm());
    const Vec3 d = v - x;
    r_max = std::max(r_max, d.norm());
    const double s = n.dot(d);
    s_min = std::min(s_min, s);
    s_max = std::max(s_max, s);
  }
  const double r_min = std::max(h, (x - centre).norm() - radius);
  const double k_max = h * std::max(0.0, s_max) / (r_min * r_min * r_min * r_min);
  const double k_min = h * std::max(0.0, s_min) / (r_max * r_max * r_max * r_max);
  return {k_min, k_max};
}

double weighted_fraction(const Visibility& visibility, const Vec3& x, const Vec3& nx, int patch_x,
                         std::span<const Vec3> polygon, const Vec3& ny, int patch_y, const std::vector<int>* occluders,
                         int samples, std::uint64_t seed, std::vector<Vec2>& uv) {
  Rng rng(seed);
  stratified_unit_square(samples, rng, &uv);
  const PolygonSampler sampler(polygon);
  double weight = 0.0, visible = 0.0;
  int seen = 0;
  for (const Vec2& u : uv) {
    const Vec3 y = sampler.point(u.x(), u.y());
    const double k = point_pair_kernel(nx, ny, y - x);
    const bool open = occluders ? !visibility.segment_blocked_among(x, patch_x, y, patch_y, *occluders)
                                : !visibility.segment_blocked(x, patch_x, y, patch_y);
    weight += k;
    visible += open ? k : 0.0;
    seen += open ? 1 : 0;
  }
  if (!(weight > 0.0)) return uv.empty() ? 1.0 : double(seen) / static_cast<double>(uv.size());
  return visible / weight;
}

double systematic_counts(std::span<const double> importance, int m, std::uint64_t seed, std::vector<int>* counts) {
  counts->assign(importance.size(), 0);
  double total = 0.0;
  for (const double v : importance) total += v;
  if (!(total > 0.0)) return 0.0;
  Rng rng(seed);
  const double offset = rng.uniform();
  double before = 0.0;
  for (std::size_t i = 0; i < importance.size(); ++i) {
    const double after = before + importance[i];
    (*counts)[i] = static_cast<int>(std::ceil(after / total * m - offset) - std::ceil(before / total * m - offset));
    before = after;
  }
  return total / m;
}

}  // namespace hrad::detail
