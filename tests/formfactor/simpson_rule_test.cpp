// The corner, edge-midpoint and centre points of elements (simpson_rule.h): their weights integrate
// polynomials exactly (bicubic on a quad's bilinear map, cubic on a triangle).
#include "hrad/formfactor/simpson_rule.h"

#include <gtest/gtest.h>

#include <vector>

#include "hrad/formfactor/polygon_quadrature.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

// A reference integral by polygon_quadrature() at a high order (exact for these degrees).
double reference(std::span<const Vec3> poly, double (*f)(const Vec3&)) {
  std::vector<detail::WeightedPoint> points;
  detail::polygon_quadrature(poly, newell_normal(poly).normalized(), 6, points);
  double sum = 0.0;
  for (const auto& p : points) sum += p.weight * f(p.x);
  return sum;
}

double simpson(std::span<const Vec3> poly, double (*f)(const Vec3&)) {
  const SimpsonPoints s = simpson_points(poly);
  double sum = 0.0;
  for (int i = 0; i < s.count; ++i) sum += s.weight[i] * f(s.x[i]);
  return sum;
}

double cubic(const Vec3& x) {
  return 1.0 + x.x() - 2.0 * x.y() + x.x() * x.y() + x.x() * x.x() * x.y() - x.y() * x.y() * x.y();
}

TEST(SimpsonRule, IntegratesCubicsOnATriangleAndOnAnAffineQuad) {
  // On a parallelogram the bilinear map is affine, so a cubic in x is a bicubic in (u, v): exact.
  const std::vector<Vec3> triangle = {{0.1, 0.2, 0}, {2.0, 0.4, 0}, {0.7, 1.9, 0}};
  const std::vector<Vec3> parallelogram = {{0, 0, 0}, {2, 0.5, 0}, {2.6, 2.0, 0}, {0.6, 1.5, 0}};
  for (const auto& poly : {triangle, parallelogram}) {
    EXPECT_NEAR(simpson(poly, cubic), reference(poly, cubic), 1e-12);
    double area = 0.0;
    for (double w : simpson_points(poly).weight) area += w;
    EXPECT_NEAR(area, polygon_area(poly), 1e-13);
  }
}

TEST(SimpsonRule, WeightsSumToTheAreaOfAPlanarQuadThatIsNoParallelogram) {
  // A trapezoid's bilinear map has an affine Jacobian: the weights integrate 1 exactly.
  const std::vector<Vec3> trapezoid = {{0, 0, 0}, {3, 0, 0}, {2, 1, 0}, {0.5, 1, 0}};
  double area = 0.0;
  for (double w : simpson_points(trapezoid).weight) area += w;
  EXPECT_NEAR(area, polygon_area(trapezoid), 1e-14);
}

}  // namespace
}  // namespace hrad
