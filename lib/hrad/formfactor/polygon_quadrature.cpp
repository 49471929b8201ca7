#include "hrad/formfactor/polygon_quadrature.h"

#include "hrad/formfactor/gauss_legendre.h"
#include "hrad/geometry/polygon.h"

namespace hrad::detail {

namespace {

// Product rule on the bilinear quadrilateral p0 p1 p2 p3.
void quad_quadrature(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, const GaussRule& g,
                     std::vector<WeightedPoint>& out) {
  const std::size_t n = g.nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double u = 0.5 * (g.nodes[i] + 1.0);
    for (std::size_t j = 0; j < n; ++j) {
      const double v = 0.5 * (g.nodes[j] + 1.0);
      const Vec3 x = (1 - u) * (1 - v) * p0 + u * (1 - v) * p1 + u * v * p2 + (1 - u) * v * p3;
      const Vec3 du = (1 - v) * (p1 - p0) + v * (p2 - p3);
      const Vec3 dv = (1 - u) * (p3 - p0) + u * (p2 - p1);
      out.push_back({x, 0.25 * g.weights[i] * g.weights[j] * du.cross(dv).norm()});
    }
  }
}

}  // namespace

void triangle_quadrature(const Vec3& a, const Vec3& b, const Vec3& c, int order, std::vector<WeightedPoint>& out) {
  const GaussRule g = gauss_legendre(order);
  const Vec3 centre = (a + b + c) / 3.0, ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
  quad_quadrature(a, ab, centre, ca, g, out);
  quad_quadrature(b, bc, centre, ab, g, out);
  quad_quadrature(c, ca, centre, bc, g, out);
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
