#include "hrad/solvers/near_field_rule.h"

#include <cmath>

#include <Eigen/Dense>

#include "hrad/formfactor/gauss_legendre.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/solvers/linear_basis.h"
#include "hrad/visibility/sampling.h"

namespace hrad {
namespace {

constexpr int kGaussPoints = 3;
// Cells of 1/2^kMaxDepth of the element's side at the finest: 1/1024 of a 2 m element is 2 mm.
constexpr int kMaxDepth = 10;

// The element's map from the unit square: a quad's bilinear map, or a triangle collapsed from the
// square as x = v0 + u (v1 - v0) + u w (v2 - v1) (Jacobian 2 A u), with the corner functions.
struct Map {
  std::span<const Vec3> v;
  Vec3 point(double u, double w, double* jacobian, std::array<double, 4>* psi) const {
    if (v.size() == 4) {
      const Vec3 xu = (1 - w) * (v[1] - v[0]) + w * (v[2] - v[3]);
      const Vec3 xv = (1 - u) * (v[3] - v[0]) + u * (v[2] - v[1]);
      *jacobian = xu.cross(xv).norm();
      *psi = {(1 - u) * (1 - w), u * (1 - w), u * w, (1 - u) * w};
      return (1 - u) * (1 - w) * v[0] + u * (1 - w) * v[1] + u * w * v[2] + (1 - u) * w * v[3];
    }
    *jacobian = (v[1] - v[0]).cross(v[2] - v[0]).norm() * u;
    *psi = {1 - u, u * (1 - w), u * w, 0.0};
    return v[0] + u * (v[1] - v[0]) + u * w * (v[2] - v[1]);
  }
};

struct Cell {
  double u0 = 0.0, w0 = 0.0, h = 1.0;
  int depth = 0;
  double sum = 0.0;  ///< the integral of the summed factors over the cell by its own Gauss points
};

// The cell's Gauss points (appended to `out`), and the integral of the summed factors over them.
double cell_points(const FormFactorEvaluator& ev, const Map& map, const Vec3& n,
                   const std::vector<std::vector<Vec3>>& sources, const Cell& c, std::vector<RulePoint>* out) {
  const detail::GaussRule g = detail::gauss_legendre(kGaussPoints);
  double sum = 0.0;
  for (int i = 0; i < kGaussPoints; ++i)
    for (int j = 0; j < kGaussPoints; ++j) {
      RulePoint p;
      double jacobian = 0.0;
      p.x = map.point(c.u0 + 0.5 * c.h * (g.nodes[static_cast<std::size_t>(i)] + 1.0),
                      c.w0 + 0.5 * c.h * (g.nodes[static_cast<std::size_t>(j)] + 1.0), &jacobian, &p.psi);
      p.weight =
          jacobian * 0.25 * c.h * c.h * g.weights[static_cast<std::size_t>(i)] * g.weights[static_cast<std::size_t>(j)];
      double f = 0.0;
      for (const std::vector<Vec3>& s : sources) f += ev.point_factor(p.x, n, s);
      sum += p.weight * f;
      out->push_back(p);
    }
  return sum;
}

}  // namespace

std::vector<RulePoint> near_field_rule(const FormFactorEvaluator& ev, std::span<const Vec3> element, const Vec3& normal,
                                       const std::vector<std::vector<Vec3>>& sources, double tolerance) {
  const Map map{element};
  std::vector<RulePoint> rule, points;
  Cell root;
  root.sum = cell_points(ev, map, normal, sources, root, &points);
  std::vector<Cell> todo{root};
  while (!todo.empty()) {
    const Cell c = todo.back();
    todo.pop_back();
    const double k = 0.5 * c.h;
    std::array<Cell, 4> quarters{Cell{c.u0, c.w0, k, c.depth + 1}, Cell{c.u0 + k, c.w0, k, c.depth + 1},
                                 Cell{c.u0, c.w0 + k, k, c.depth + 1}, Cell{c.u0 + k, c.w0 + k, k, c.depth + 1}};
    points.clear();
    double parts = 0.0;
    for (Cell& q : quarters) parts += (q.sum = cell_points(ev, map, normal, sources, q, &points));
    // The root is always cut once, so that the rule has at least four cells.
    if ((c.depth > 0 && std::abs(parts - c.sum) <= tolerance) || c.depth + 1 >= kMaxDepth)
      rule.insert(rule.end(), points.begin(), points.end());
    else
      for (const Cell& q : quarters) todo.push_back(q);
  }
  return rule;
}

std::array<double, 4> rule_moments(const FormFactorEvaluator& ev, const std::vector<RulePoint>& rule,
                                   const Vec3& normal, int patch, std::span<const Vec3> source, int source_patch,
                                   const std::vector<int>* occluders, bool partial, std::uint64_t seed) {
  std::array<double, 4> m{};
  for (std::size_t k = 0; k < rule.size(); ++k) {
    const RulePoint& p = rule[k];
    double f = ev.point_factor(p.x, normal, source);
    if (partial && f > 0.0) {
      const KernelVisibility v = ev.visibility_from_point(p.x, normal, patch, source, source_patch, occluders, 1,
                                                          detail::mix_seed(seed, static_cast<std::uint64_t>(k)));
      f *= v.weight > 0.0 ? v.visible / v.weight : 0.5;
    }
    for (int a = 0; a < 4; ++a) m[static_cast<std::size_t>(a)] += p.psi[static_cast<std::size_t>(a)] * f * p.weight;
  }
  return m;
}

void match_linear_moments(const SimpsonPoints& s, const std::array<double, 4>& target, std::array<double, 9>* values) {
  const int vertex_count = s.count == 9 ? 4 : 3;
  const int n = linear_corners(vertex_count);
  std::array<double, 9>& f = *values;
  if (s.count == 7) f[6] = triangle_quadratic_centre(f);
  Eigen::Matrix4d mass = Eigen::Matrix4d::Identity();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  for (int a = 0; a < n; ++a) {
    double moment = 0.0;
    for (int k = 0; k < s.count; ++k)
      moment +=
          s.weight[static_cast<std::size_t>(k)] * linear_function(vertex_count, a, k) * f[static_cast<std::size_t>(k)];
    rhs(a) = target[static_cast<std::size_t>(a)] - moment;
    for (int b = 0; b < n; ++b) {
      double m = 0.0;
      for (int k = 0; k < s.count; ++k)
        m += s.weight[static_cast<std::size_t>(k)] * linear_function(vertex_count, a, k) *
             linear_function(vertex_count, b, k);
      mass(a, b) = m;
    }
  }
  const Eigen::Vector4d c = mass.ldlt().solve(rhs);
  for (int k = 0; k < s.count; ++k)
    for (int a = 0; a < n; ++a) f[static_cast<std::size_t>(k)] += c(a) * linear_function(vertex_count, a, k);
}

}  // namespace hrad
