#include "hrad/visibility/solid_angle_sampler.h"

#include <algorithm>
#include <cmath>

#include "hrad/geometry/polygon.h"

namespace hrad::detail {
namespace {

// The unit vector along the part of `v` orthogonal to the unit vector `a`.
Vec3 orthonormal(const Vec3& v, const Vec3& a) { return (v - v.dot(a) * a).normalized(); }

}  // namespace

SolidAngleSampler::SolidAngleSampler(const Vec3& x, std::span<const Vec3> polygon) : x_(x) {
  if (polygon.size() < 3) return;
  const Vec3 n = newell_normal(polygon);
  if (!(n.squaredNorm() > 0.0)) return;
  normal_ = n.normalized();
  offset_ = normal_.dot(polygon[0] - x);
  if (offset_ == 0.0) return;  // x in the polygon's plane: seen edge-on
  const Vec3 a = (polygon[0] - x).normalized();
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    Triangle t;
    t.a = a;
    t.b = (polygon[i] - x).normalized();
    t.c = (polygon[i + 1] - x).normalized();
    // Solid angle of a spherical triangle (Van Oosterom & Strackee 1983) and its angle at a,
    // both from atan2 so that thin triangles keep their digits.
    const double det = std::abs(t.a.dot(t.b.cross(t.c)));
    t.cos_ab = t.a.dot(t.b);
    const double ac = t.a.dot(t.c), bc = t.b.dot(t.c);
    t.solid_angle = 2.0 * std::atan2(det, 1.0 + t.cos_ab + bc + ac);
    t.alpha = std::atan2(det, bc - t.cos_ab * ac);
    if (!(t.solid_angle > 0.0) || !(t.alpha > 0.0)) continue;
    solid_angle_ += t.solid_angle;
    triangles_.push_back(t);
  }
}

bool SolidAngleSampler::sample(double u, double v, Vec3* direction, Vec3* point) const {
  if (triangles_.empty()) return false;
  // Pick a triangle by solid angle and remap u into it (stratification survives the pick).
  double area = u * solid_angle_;
  std::size_t k = 0;
  while (k + 1 < triangles_.size() && area > triangles_[k].solid_angle) area -= triangles_[k++].solid_angle;
  const Triangle& t = triangles_[k];
  area = std::clamp(area, 0.0, t.solid_angle);
  // Arvo (1995), figure 2: the point c_hat on the arc from a to c that cuts off the sub-triangle
  // (a, b, c_hat) of solid angle `area`, then a point on the arc from b to c_hat.
  const double s = std::sin(area - t.alpha), co = std::cos(area - t.alpha);
  const double cos_alpha = std::cos(t.alpha), sin_alpha = std::sin(t.alpha);
  const double uu = co - cos_alpha, vv = s + sin_alpha * t.cos_ab;
  const double denominator = (vv * s + uu * co) * sin_alpha;
  if (denominator == 0.0) return false;
  const double q = std::clamp(((vv * co - uu * s) * cos_alpha - vv) / denominator, -1.0, 1.0);
  const Vec3 c_hat = q * t.a + std::sqrt(1.0 - q * q) * orthonormal(t.c, t.a);
  const double z = std::clamp(1.0 - v * (1.0 - c_hat.dot(t.b)), -1.0, 1.0);
  const Vec3 d = (z * t.b + std::sqrt(1.0 - z * z) * orthonormal(c_hat, t.b)).normalized();
  const double along = normal_.dot(d);
  // The plane lies at signed distance offset_ along its normal; the ray meets it ahead of x only
  // when the two have one sign.
  if (!(along * offset_ > 0.0)) return false;
  *direction = d;
  *point = x_ + (offset_ / along) * d;
  return true;
}

}  // namespace hrad::detail
