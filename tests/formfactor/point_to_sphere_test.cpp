// The factor from a differential planar element to a sphere (point_to_sphere()) against its closed
// forms and an independent quadrature over the sphere's solid angle.
#include "hrad/formfactor/point_to_sphere.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace hrad {
namespace {

// F by quadrature: (1/pi) sum over the sphere's cap of max(0, n.w) dw, midpoint rule in (cos, phi)
// about the centre direction.
double by_quadrature(const Vec3& n, const Vec3& towards, double h) {
  const double cos_sigma = std::sqrt(1.0 - 1.0 / (h * h));
  const Vec3 c = towards.normalized(), t = c.unitOrthogonal(), b = c.cross(t);
  const int nu = 1000, nphi = 3000;
  double sum = 0.0;
  for (int i = 0; i < nu; ++i) {
    const double u = 1.0 - (i + 0.5) / nu * (1.0 - cos_sigma), s = std::sqrt(1.0 - u * u);
    for (int k = 0; k < nphi; ++k) {
      const double phi = 2.0 * std::numbers::pi * (k + 0.5) / nphi;
      sum += std::max(0.0, n.dot(u * c + s * std::cos(phi) * t + s * std::sin(phi) * b));
    }
  }
  const double solid = 2.0 * std::numbers::pi * (1.0 - cos_sigma);
  return sum / (nu * nphi) * solid / std::numbers::pi;
}

// Guarantee: above the horizon F = cos(phi) / H^2 to rounding; across it, F(n) - F(-n) =
// cos(phi) / H^2 (the signed cosine integrates to the projected disc) and F within 1e-5 relative of
// a quadrature over the cap; below it 0; inside the sphere 1.
TEST(PointToSphere, ClosedFormsAndQuadratureAcrossTheHorizon) {
  const Vec3 x(0.2, -0.3, 0.5), centre(2.2, 1.7, 0.5);
  const double distance = (centre - x).norm();
  for (const double h : {1.2, 2.0, 5.0, 40.0}) {
    const double radius = distance / h;
    for (const double phi : {0.0, 0.4, 1.3, 1.5, 1.5707963, 1.7, 2.2, 3.0}) {
      const Vec3 c = (centre - x) / distance, t = c.unitOrthogonal();
      const Vec3 n = std::cos(phi) * c + std::sin(phi) * t;
      const double f = point_to_sphere(x, n, centre, radius), back = point_to_sphere(x, -n, centre, radius);
      EXPECT_NEAR(f - back, std::cos(phi) / (h * h), 1e-12) << h << " " << phi;
      if (h * std::cos(phi) >= 1.0) EXPECT_NEAR(f, std::cos(phi) / (h * h), 1e-15) << h << " " << phi;
      if (h * std::cos(phi) <= -1.0) EXPECT_EQ(f, 0.0) << h << " " << phi;
      if (std::abs(h * std::cos(phi)) < 1.0)
        EXPECT_NEAR(f / by_quadrature(n, centre - x, h), 1.0, 1e-5) << h << " " << phi;
    }
  }
  EXPECT_EQ(point_to_sphere(x, Vec3::UnitY(), x + Vec3(0.1, 0, 0), 0.5), 1.0);
}

}  // namespace
}  // namespace hrad
