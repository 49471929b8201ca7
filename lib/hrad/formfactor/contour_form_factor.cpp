#include "hrad/formfactor/contour_form_factor.h"

#include <cmath>
#include <numbers>

#include "hrad/formfactor/edge_pair_integral.h"

namespace hrad::detail {

ContourSum contour_area_factor(std::span<const Vec3> from, std::span<const Vec3> to) {
  double sum = 0.0, magnitude = 0.0;
  const std::size_t m = from.size(), n = to.size();
  for (std::size_t i = 0; i < m; ++i) {
    const Vec3& p0 = from[i];
    const Vec3& p1 = from[i + 1 == m ? 0 : i + 1];
    const Vec3 a = p1 - p0;
    const double lp = a.norm();
    for (std::size_t j = 0; j < n; ++j) {
      const Vec3& q0 = to[j];
      const Vec3& q1 = to[j + 1 == n ? 0 : j + 1];
      const double lq = (q1 - q0).norm();
      const double cos_length = a.dot(q1 - q0);  // (a . b) Lp Lq
      if (cos_length == 0.0) continue;           // perpendicular edges contribute nothing
      const double cosine = cos_length / (lp * lq);
      const EdgePairIntegral k = edge_pair_log_integral(p0, p1, q0, q1);
      sum += cosine * k.value;
      magnitude += std::abs(cosine) * k.magnitude;
    }
  }
  // Both contours counter-clockwise about their own fronts, which face each other.
  return {sum / (2.0 * std::numbers::pi), magnitude / (2.0 * std::numbers::pi)};
}

}  // namespace hrad::detail
