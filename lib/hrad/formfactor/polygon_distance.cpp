#include "hrad/formfactor/polygon_distance.h"

#include <algorithm>
#include <cmath>

#include "hrad/geometry/polygon.h"

namespace hrad::detail {
namespace {

// Closest points of two segments (Ericson 2005, Real-Time Collision Detection, sec. 5.1.9).
double segment_distance(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a == 0.0 && e == 0.0) return r.norm();
  if (a == 0.0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e == 0.0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p1 + s * d1) - (p2 + t * d2)).norm();
}

// Distance from x to the polygon's interior when its projection falls inside (winding number in
// the polygon's plane), else infinity (the boundary is covered by the edge-edge distances).
double projected_distance(const Vec3& x, std::span<const Vec3> p, const Vec3& n) {
  const auto [u, v] = plane_basis(n);
  int winding = 0;
  const std::size_t k = p.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3 a3 = p[i] - x, b3 = p[(i + 1) % k] - x;
    const double ax = a3.dot(u), ay = a3.dot(v), bx = b3.dot(u), by = b3.dot(v);
    const double cross = ax * by - ay * bx;
    if (ay <= 0.0) {
      if (by > 0.0 && cross > 0.0) ++winding;
    } else if (by <= 0.0 && cross < 0.0) {
      --winding;
    }
  }
  return winding != 0 ? std::abs(n.dot(p[0] - x)) : INFINITY;
}

}  // namespace

double polygon_distance(std::span<const Vec3> a, const Vec3& na, std::span<const Vec3> b, const Vec3& nb) {
  double d = INFINITY;
  for (const Vec3& x : a) d = std::min(d, projected_distance(x, b, nb));
  for (const Vec3& x : b) d = std::min(d, projected_distance(x, a, na));
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      d = std::min(d, segment_distance(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()]));
  return d;
}

}  // namespace hrad::detail
