#include "hrad/formfactor/point_to_polygon_limit.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "hrad/formfactor/clip_polygon.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/geometry/polygon.h"

namespace hrad {

double point_to_polygon_limit(const Vec3& x, const Vec3& n, const Vec3& d, std::span<const Vec3> polygon,
                              double rel_tol) {
  const std::size_t k = polygon.size();
  if (k < 3) return 0.0;
  const Vec3 normal = newell_normal(polygon);
  const double normal_length = normal.norm();
  if (!(normal_length > 0.0)) return 0.0;
  // Signed distance of x from the polygon's plane, at the nearest vertex (as point_to_polygon()).
  double nearest = INFINITY, distance = 0.0;
  for (const Vec3& v : polygon) {
    const double r = (v - x).norm();
    if (r < nearest) {
      nearest = r;
      distance = normal.dot(x - v) / normal_length;
    }
  }
  if (distance > 1e-12 * nearest) return point_to_polygon(x, n, polygon, rel_tol);  // strictly in front
  // x' = x + t d must come from the front of the polygon's plane.
  if (!(normal.dot(d) > 0.0) || distance < -1e-12 * nearest) return 0.0;
  // In the plane: clip to x's closed front half-space, then Lambert's sum in the limit.
  thread_local std::vector<Vec3> r, clipped;
  thread_local std::vector<double> height;
  r.resize(k);
  height.resize(k);
  bool any_above = false;
  for (std::size_t i = 0; i < k; ++i) {
    r[i] = polygon[i] - x;
    height[i] = n.dot(r[i]);
    any_above |= height[i] > 0.0;
  }
  if (!any_above) return 0.0;
  detail::clip_to_half_space(r, height, clipped);
  const std::size_t m = clipped.size();
  if (m < 3) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    // The directions from x' to the edge's ends: a vertex at x is seen along -d.
    const Vec3 a = clipped[i].squaredNorm() > 0.0 ? clipped[i] : Vec3(-d);
    const Vec3 b = clipped[i + 1 == m ? 0 : i + 1].squaredNorm() > 0.0 ? clipped[i + 1 == m ? 0 : i + 1] : Vec3(-d);
    const Vec3 c = b.cross(a);
    const double s = c.norm();
    if (s > 0.0) {
      sum += std::atan2(s, a.dot(b)) * n.dot(c) / s;
    } else if (a.dot(b) < 0.0) {
      // x strictly inside the edge: R_{i+1} x R_i -> -t (b - a) x d, at the angle pi.
      const Vec3 limit = d.cross(b - a);
      const double l = limit.norm();
      if (l > 0.0) sum += std::numbers::pi * n.dot(limit) / l;
    }
  }
  return std::max(0.0, sum / (2.0 * std::numbers::pi));
}

}  // namespace hrad
