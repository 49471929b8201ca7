#include "hrad/formfactor/polygon_quadrature.h"

#include "hrad/formfactor/gauss_legendre.h"
#include "hrad/geometry/polygon.h"

namespace hrad::detail {

void triangle_quadrature(const Vec3& a, const Vec3& b, const Vec3& c, int order, std::vector<WeightedPoint>& out) {
  const GaussRule g = gauss_legendre(order);
  const double area2 = (b - a).cross(c - a).norm();
  // x(u, v) = a + u (b - a) + u v (c - b), u, v in [0, 1]; dA = u * 2 area du dv.
  for (int i = 0; i < order; ++i) {
    const double u = 0.5 * (g.nodes[i] + 1.0);
    const Vec3 p = a + u * (b - a);
    const Vec3 q = u * (c - b);
    for (int j = 0; j < order; ++j) {
      const double v = 0.5 * (g.nodes[j] + 1.0);
      out.push_back({p + v * q, 0.25 * g.weights[i] * g.weights[j] * u * area2});
    }
  }
}

void polygon_quadrature(std::span<const Vec3> polygon, const Vec3& unit_normal, int order,
                        std::vector<WeightedPoint>& out) {
  if (polygon.size() == 3) {
    triangle_quadrature(polygon[0], polygon[1], polygon[2], order, out);
    return;
  }
  for (const auto& t : triangulate(polygon, unit_normal))
    triangle_quadrature(polygon[t[0]], polygon[t[1]], polygon[t[2]], order, out);
}

}  // namespace hrad::detail
