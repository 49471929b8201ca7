#include "hrad/formfactor/point_to_sphere.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hrad {

double point_to_sphere(const Vec3& x, const Vec3& n, const Vec3& centre, double radius) {
  const Vec3 to_centre = centre - x;
  const double distance = to_centre.norm();
  if (!(distance > radius)) return 1.0;
  const double h = distance / radius;
  const double cos_phi = std::clamp(n.dot(to_centre) / distance, -1.0, 1.0);
  const double h2 = h * h;
  // Wholly above or wholly below the horizon: |cos phi| >= sin(sigma) = 1 / H.
  if (h * cos_phi >= 1.0) return cos_phi / h2;
  if (h * cos_phi <= -1.0) return 0.0;
  const double sin_phi = std::sqrt(std::max(0.0, 1.0 - cos_phi * cos_phi));
  const double root = std::sqrt(h2 - 1.0);
  const double pi = std::numbers::pi;
  const double f = 0.5 - std::asin(std::clamp(root / (h * sin_phi), -1.0, 1.0)) / pi +
                   cos_phi * std::acos(std::clamp(-root * cos_phi / sin_phi, -1.0, 1.0)) / (pi * h2) -
                   root * std::sqrt(std::max(0.0, 1.0 - h2 * cos_phi * cos_phi)) / (pi * h2);
  return std::max(0.0, f);
}

}  // namespace hrad
