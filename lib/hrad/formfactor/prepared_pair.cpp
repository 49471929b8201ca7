#include "hrad/formfactor/prepared_pair.h"

#include <cmath>
#include <limits>

#include "hrad/formfactor/clip_polygon.h"
#include "hrad/geometry/polygon.h"

namespace hrad::detail {
namespace {

double reach(std::span<const Vec3> p) {
  double r = 0.0;
  for (const Vec3& v : p) r = std::max(r, (v - p[0]).norm());
  return r;
}

// Signed distances of `p`'s vertices to the plane of `q` (unit normal n). Each is taken from q's
// vertex nearest to it, so vertices shared by both polygons get exactly 0. A distance within the
// rounding of the input and of its own evaluation (a few ulps of the input coordinates' magnitude,
// `input_ulp`, and of the lever arm) is set to 0: the plane is not known better than that, and this
// makes coplanar pairs exactly 0 rather than a sliver of rounding noise.
void plane_distances(std::span<const Vec3> p, std::span<const Vec3> q, const Vec3& n, double input_ulp,
                     std::vector<double>& d) {
  constexpr double kUlps = 16.0 * std::numeric_limits<double>::epsilon();
  d.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::size_t nearest = 0;
    double best = INFINITY;
    for (std::size_t j = 0; j < q.size(); ++j) {
      const double d2 = (p[i] - q[j]).squaredNorm();
      if (d2 < best) best = d2, nearest = j;
    }
    const Vec3 arm = p[i] - q[nearest];
    const double h = n.dot(arm);
    d[i] = std::abs(h) <= kUlps * arm.lpNorm<Eigen::Infinity>() + input_ulp ? 0.0 : h;
  }
}

bool any_positive(const std::vector<double>& d) {
  for (double x : d)
    if (x > 0.0) return true;
  return false;
}

}  // namespace

PreparedPair prepare_pair(std::span<const Vec3> from, std::span<const Vec3> to) {
  PreparedPair pair;
  if (from.size() < 3 || to.size() < 3) return pair;
  pair.from_area = polygon_area(from);
  pair.to_area = polygon_area(to);
  const double scale = std::max(reach(from), reach(to));
  if (!(pair.from_area > 0.0) || !(pair.to_area > 0.0) || !(scale > 0.0) || !std::isfinite(scale)) return pair;
  pair.scale = scale;
  const Vec3 origin = from[0];
  double magnitude = 0.0;
  for (const Vec3& v : from) magnitude = std::max(magnitude, v.lpNorm<Eigen::Infinity>());
  for (const Vec3& v : to) magnitude = std::max(magnitude, v.lpNorm<Eigen::Infinity>());
  const double input_ulp = 16.0 * std::numeric_limits<double>::epsilon() * magnitude / scale;
  thread_local std::vector<Vec3> f, t;
  thread_local std::vector<double> d;
  f.clear();
  t.clear();
  for (const Vec3& v : from) f.push_back((v - origin) / scale);
  for (const Vec3& v : to) t.push_back((v - origin) / scale);
  pair.from_normal = newell_normal(f).normalized();
  pair.to_normal = newell_normal(t).normalized();
  plane_distances(f, t, pair.to_normal, input_ulp, d);
  if (!any_positive(d)) return pair;  // from is behind or in to's plane
  clip_to_half_space(f, d, pair.from);
  plane_distances(t, f, pair.from_normal, input_ulp, d);
  if (!any_positive(d)) return pair;
  clip_to_half_space(t, d, pair.to);
  pair.visible = pair.from.size() >= 3 && pair.to.size() >= 3;
  return pair;
}

}  // namespace hrad::detail
