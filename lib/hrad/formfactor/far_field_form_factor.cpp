#include "hrad/formfactor/far_field_form_factor.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "hrad/formfactor/polygon_quadrature.h"

namespace hrad::detail {

int far_field_order(double distance, double radius_from, double radius_to, double rel_tol) {
  const double radius = std::max(radius_from, radius_to);
  const double gap = distance - radius_from - radius_to;
  if (!(gap > 0.0)) return 0;
  const double d = (gap + radius) / radius;  // nearest singularity, in panel half-widths
  const double rho = d + std::sqrt(d * d + 1.0);
  const int order = static_cast<int>(std::ceil(0.5 * std::log(1.0 / rel_tol) / std::log(rho)));
  return order <= kMaxFarOrder ? std::max(order, 2) : 0;
}

double far_field_area_factor(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& na, const Vec3& b0,
                             const Vec3& b1, const Vec3& b2, const Vec3& nb, int order) {
  thread_local std::vector<WeightedPoint> pa, pb;
  pa.clear();
  pb.clear();
  triangle_quadrature(a0, a1, a2, order, pa);
  triangle_quadrature(b0, b1, b2, order, pb);
  double sum = 0.0;
  for (const WeightedPoint& x : pa) {
    double inner = 0.0;
    for (const WeightedPoint& y : pb) {
      const Vec3 v = y.x - x.x;
      const double r2 = v.squaredNorm();
      inner += y.weight * (na.dot(v) * -nb.dot(v)) / (r2 * r2);
    }
    sum += x.weight * inner;
  }
  return sum / std::numbers::pi;
}

}  // namespace hrad::detail
