#include "hrad/formfactor/quadrature_form_factor.h"

#include <cmath>
#include <queue>
#include <vector>

#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/formfactor/polygon_quadrature.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

constexpr int kOrder = 5;

struct Cell {
  Vec3 a, b, c;
  double value;  // this triangle's integral, from its four children
  double error;  // |one-rule estimate - four-children estimate|
  bool operator<(const Cell& o) const { return error < o.error; }
};

struct Integrator {
  Vec3 normal;
  std::span<const Vec3> to;
  std::size_t evaluations = 0;
  std::vector<detail::WeightedPoint> points;

  double rule(const Vec3& a, const Vec3& b, const Vec3& c) {
    points.clear();
    detail::triangle_quadrature(a, b, c, kOrder, points);
    double sum = 0.0;
    for (const auto& p : points) sum += p.weight * point_to_polygon(p.x, normal, to);
    evaluations += points.size();
    return sum;
  }

  Cell cell(const Vec3& a, const Vec3& b, const Vec3& c, double coarse) {
    const Vec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    const double fine = rule(a, ab, ca) + rule(ab, b, bc) + rule(ca, bc, c) + rule(ab, bc, ca);
    return {a, b, c, fine, std::abs(fine - coarse)};
  }
};

}  // namespace

QuadratureFormFactor quadrature_form_factor(std::span<const Vec3> from, std::span<const Vec3> to, double rel_tol,
                                            std::size_t max_evaluations) {
  QuadratureFormFactor result;
  if (from.size() < 3 || to.size() < 3) return result;
  const double area = polygon_area(from);
  if (!(area > 0.0)) return result;
  // Relative to a vertex of `from` and scaled, like the kernels, so that no unit is preferred.
  const double scale = polygon_diameter(from);
  std::vector<Vec3> f, t;
  for (const Vec3& v : from) f.push_back((v - from[0]) / scale);
  for (const Vec3& v : to) t.push_back((v - from[0]) / scale);
  const Vec3 normal = newell_normal(f).normalized();
  Integrator in{normal, t, 0, {}};
  std::priority_queue<Cell> queue;
  double total = 0.0, error = 0.0;
  for (const auto& tri : triangulate(f, normal)) {
    const Vec3 &a = f[tri[0]], &b = f[tri[1]], &c = f[tri[2]];
    const Cell cell = in.cell(a, b, c, in.rule(a, b, c));
    total += cell.value;
    error += cell.error;
    queue.push(cell);
  }
  // Global subdivision: always refine the cell with the largest error estimate.
  while (!queue.empty() && error > rel_tol * std::abs(total) && in.evaluations < max_evaluations) {
    const Cell worst = queue.top();
    queue.pop();
    total -= worst.value;
    error -= worst.error;
    const Vec3 &a = worst.a, &b = worst.b, &c = worst.c;
    const Vec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    for (const auto& [x, y, z] :
         {std::array{a, ab, ca}, std::array{ab, b, bc}, std::array{ca, bc, c}, std::array{ab, bc, ca}}) {
      const Cell child = in.cell(x, y, z, in.rule(x, y, z));
      total += child.value;
      error += child.error;
      queue.push(child);
    }
    error = std::max(error, 0.0);
  }
  result.value = std::max(total, 0.0) * scale * scale / area;
  result.error_estimate = error * scale * scale / area;
  result.evaluations = in.evaluations;
  result.converged = error <= rel_tol * std::abs(total);
  return result;
}

}  // namespace hrad
