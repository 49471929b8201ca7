// Differential area to polygon: Lambert's contour formula (Lambert 1760; Nusselt 1928), in the form
//   F = 1/(2 pi) * sum_i gamma_i * n . (R_{i+1} x R_i) / |R_{i+1} x R_i|
// with R_i = v_i - x and gamma_i the angle between R_i and R_{i+1} (Cohen & Wallace 1993, eq. 4.16;
// Baum, Rushmeier & Winget 1989, eq. 4). The sign follows from the polygon's counter-clockwise order
// seen from its front. The formula assumes the whole polygon above x's tangent plane, so the polygon
// is first clipped to that half-space. Everything is relative to x and homogeneous of degree 0 in the
// R_i, so the result does not depend on the unit of length.
#include "hrad/formfactor/point_to_polygon.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "hrad/formfactor/clip_polygon.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

// Sum over the closed contour; `r` are the vertices relative to x.
double lambert_sum(std::span<const Vec3> r, const Vec3& n) {
  double sum = 0.0;
  const std::size_t k = r.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& a = r[i];
    const Vec3& b = r[i + 1 == k ? 0 : i + 1];
    const Vec3 c = b.cross(a);
    const double s = c.norm();
    // s == 0: x on the edge's line. Outside the segment gamma = 0; on it x would lie in the
    // polygon's plane, which the caller has excluded. Either way the term is 0.
    if (s > 0.0) sum += std::atan2(s, a.dot(b)) * n.dot(c) / s;
  }
  return sum / (2.0 * std::numbers::pi);
}

}  // namespace

double point_to_polygon(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon) {
  const std::size_t k = polygon.size();
  if (k < 3) return 0.0;
  thread_local std::vector<Vec3> r, clipped;
  thread_local std::vector<double> height;
  r.resize(k);
  height.resize(k);
  bool any_above = false, any_below = false;
  std::size_t nearest = 0;
  double nearest_d2 = INFINITY;
  for (std::size_t i = 0; i < k; ++i) {
    r[i] = polygon[i] - x;
    height[i] = n.dot(r[i]);
    any_above |= height[i] > 0.0;
    any_below |= height[i] < 0.0;
    const double d2 = r[i].squaredNorm();
    if (d2 < nearest_d2) nearest_d2 = d2, nearest = i;
  }
  if (!any_above) return 0.0;  // behind or in the tangent plane
  // x must be strictly in front of the polygon (its plane evaluated at the vertex nearest x).
  const Vec3 normal = newell_normal(r);
  if (!(normal.dot(r[nearest]) < 0.0)) return 0.0;
  if (!any_below) return std::max(0.0, lambert_sum(r, n));
  detail::clip_to_half_space(r, height, clipped);
  if (clipped.size() < 3) return 0.0;
  return std::max(0.0, lambert_sum(clipped, n));
}

}  // namespace hrad
