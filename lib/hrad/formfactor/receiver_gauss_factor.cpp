#include "hrad/formfactor/receiver_gauss_factor.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "hrad/formfactor/gauss_legendre.h"
#include "hrad/formfactor/simpson_rule.h"
#include "hrad/geometry/polygon.h"

namespace hrad {

double NearEdge::distance(const Vec3& x) const {
  const Vec3 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((x - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (x - (a + t * d)).norm();
}

namespace {

// Cells of the plain rule along a quad's u (axis 0) or v (axis 1) side: k where the sides' ratio is
// between sqrt(2) (k - 1/2) and sqrt(2) (k + 1/2): cells of aspect below ~2, and thresholds
// irrational, so that no ratio of short decimal or binary lengths sits on one (a scaled scene rounds
// its lengths and must keep its rules).
int quad_cells(std::span<const Vec3> p, int axis) {
  const double lu = 0.5 * ((p[1] - p[0]).norm() + (p[2] - p[3]).norm());
  const double lv = 0.5 * ((p[3] - p[0]).norm() + (p[2] - p[1]).norm());
  const double along = axis == 0 ? lu : lv, across = axis == 0 ? lv : lu;
  if (!(across > 0.0)) return 1;
  const auto k = static_cast<long>(std::floor(along / across / std::numbers::sqrt2 + 0.5));
  return static_cast<int>(std::clamp(k, 1L, kMaxReceiverCells));
}

}  // namespace

void receiver_gauss_points(std::span<const Vec3> p, const Vec3& n, std::vector<detail::WeightedPoint>& out) {
  out.clear();
  if (p.size() != 4) {
    detail::polygon_quadrature(p, n, 2, out);
    return;
  }
  // An elongated quad takes the rule on each of a row of near-square cells of its parameter square:
  // one 3 x 3 rule spread over a long element puts its points far from where the light of a polygon
  // near one end arrives (the elements along a corridor from its end wall). The points still do not
  // depend on the source, so closure holds as before.
  const int mu = quad_cells(p, 0), mv = quad_cells(p, 1);
  const detail::GaussRule g = detail::gauss_legendre(3);
  for (int a = 0; a < mu; ++a)
    for (std::size_t i = 0; i < g.nodes.size(); ++i) {
      const double u = (a + 0.5 * (g.nodes[i] + 1.0)) / mu;
      for (int b = 0; b < mv; ++b)
        for (std::size_t j = 0; j < g.nodes.size(); ++j) {
          const double v = (b + 0.5 * (g.nodes[j] + 1.0)) / mv;
          const Vec3 x = (1 - u) * (1 - v) * p[0] + u * (1 - v) * p[1] + u * v * p[2] + (1 - u) * v * p[3];
          const Vec3 du = (1 - v) * (p[1] - p[0]) + v * (p[2] - p[3]);
          const Vec3 dv = (1 - u) * (p[3] - p[0]) + u * (p[2] - p[1]);
          out.push_back({x, 0.25 * g.weights[i] * g.weights[j] * du.cross(dv).norm() / (mu * mv)});
        }
    }
}

namespace {

// True when some near edge that grades cells of this depth passes within `radius` of `centre`
// (through a cell's bounding sphere).
bool near_edge_within(const Vec3& centre, double radius, int depth, std::span<const NearEdge> near) {
  for (const NearEdge& e : near)
    if (depth < e.max_depth && e.distance(centre) < radius) return true;
  return false;
}

// The area element of the bilinear map of the quad p (bilinear_point()) at (u, v).
double bilinear_jacobian(std::span<const Vec3> p, double u, double v) {
  const Vec3 du = (1 - v) * (p[1] - p[0]) + v * (p[2] - p[3]);
  const Vec3 dv = (1 - u) * (p[3] - p[0]) + u * (p[2] - p[1]);
  return du.cross(dv).norm();
}

// The quad's parameter cell [u0, u1] x [v0, v1], cut into four while a near edge passes through its
// bounding sphere; the 3 x 3 product rule on each cell kept.
void graded_quad_cell(std::span<const Vec3> p, double u0, double u1, double v0, double v1, int depth,
                      std::span<const NearEdge> near, const detail::GaussRule& g,
                      std::vector<detail::WeightedPoint>& out) {
  const Vec3 centre = bilinear_point(p, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
  double radius = 0.0;
  for (const auto& [u, v] : {std::pair{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}})
    radius = std::max(radius, (bilinear_point(p, u, v) - centre).norm());
  if (near_edge_within(centre, radius, depth, near)) {
    const double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
    graded_quad_cell(p, u0, um, v0, vm, depth + 1, near, g, out);
    graded_quad_cell(p, um, u1, v0, vm, depth + 1, near, g, out);
    graded_quad_cell(p, um, u1, vm, v1, depth + 1, near, g, out);
    graded_quad_cell(p, u0, um, vm, v1, depth + 1, near, g, out);
    return;
  }
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    const double u = u0 + (u1 - u0) * 0.5 * (g.nodes[i] + 1.0);
    for (std::size_t j = 0; j < g.nodes.size(); ++j) {
      const double v = v0 + (v1 - v0) * 0.5 * (g.nodes[j] + 1.0);
      out.push_back({bilinear_point(p, u, v),
                     0.25 * g.weights[i] * g.weights[j] * bilinear_jacobian(p, u, v) * (u1 - u0) * (v1 - v0)});
    }
  }
}

// The triangle (a, b, c), cut at its edge midpoints while a near edge passes through its bounding
// sphere (about its centroid); the order-2 rule of polygon_quadrature() on each triangle kept.
void graded_triangle(const Vec3& a, const Vec3& b, const Vec3& c, int depth, std::span<const NearEdge> near,
                     std::vector<detail::WeightedPoint>& out) {
  const Vec3 centre = (a + b + c) / 3.0;
  const double radius = std::max({(a - centre).norm(), (b - centre).norm(), (c - centre).norm()});
  if (near_edge_within(centre, radius, depth, near)) {
    const Vec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    graded_triangle(a, ab, ca, depth + 1, near, out);
    graded_triangle(ab, b, bc, depth + 1, near, out);
    graded_triangle(ca, bc, c, depth + 1, near, out);
    graded_triangle(ab, bc, ca, depth + 1, near, out);
    return;
  }
  detail::triangle_quadrature(a, b, c, 2, out);
}

}  // namespace

void receiver_gauss_points(std::span<const Vec3> p, const Vec3& n, std::span<const NearEdge> near,
                           std::vector<detail::WeightedPoint>& out) {
  if (near.empty()) {
    receiver_gauss_points(p, n, out);
    return;
  }
  out.clear();
  if (p.size() != 4) {
    if (p.size() == 3) {
      graded_triangle(p[0], p[1], p[2], 0, near, out);
      return;
    }
    for (const auto& t : triangulate(p, n)) graded_triangle(p[t[0]], p[t[1]], p[t[2]], 0, near, out);
    return;
  }
  const int mu = quad_cells(p, 0), mv = quad_cells(p, 1);
  const detail::GaussRule g = detail::gauss_legendre(3);
  for (int a = 0; a < mu; ++a)
    for (int b = 0; b < mv; ++b)
      graded_quad_cell(p, static_cast<double>(a) / mu, static_cast<double>(a + 1) / mu, static_cast<double>(b) / mv,
                       static_cast<double>(b + 1) / mv, 0, near, g, out);
}

double receiver_gauss_factor(std::span<const Vec3> receiver, std::span<const Vec3> source, double rel_tol,
                             int* point_count) {
  return receiver_gauss_factor(receiver, source, {}, rel_tol, point_count);
}

double receiver_gauss_factor(std::span<const Vec3> receiver, std::span<const Vec3> source,
                             std::span<const NearEdge> near, double rel_tol, int* point_count) {
  thread_local std::vector<detail::WeightedPoint> points;
  const Vec3 n = newell_normal(receiver).normalized();
  receiver_gauss_points(receiver, n, near, points);
  if (point_count != nullptr) *point_count = static_cast<int>(points.size());
  double sum = 0.0, area = 0.0;
  for (const detail::WeightedPoint& p : points) {
    sum += p.weight * point_to_polygon(p.x, n, source, rel_tol);
    area += p.weight;  // the weights' own sum, so that factors to a closed surface sum to 1 exactly
  }
  return area > 0.0 ? std::max(0.0, sum / area) : 0.0;
}

double receiver_factor_by_distance(std::span<const Vec3> receiver, std::span<const Vec3> source, double centroid_ratio,
                                   int* point_count) {
  const auto [rc, rr] = vertex_sphere(receiver);
  const auto [sc, sr] = vertex_sphere(source);
  const double gap = (rc - sc).norm() - rr - sr;
  if (!(gap > 0.0) || 2.0 * rr > centroid_ratio * gap)
    return receiver_gauss_factor(receiver, source, kLambertSumOnly, point_count);
  if (point_count != nullptr) *point_count = 1;
  // A quad's bilinear centre and a triangle's centroid are the vertices' mean; other polygons
  // take the area centroid.
  const Vec3 x = receiver.size() <= 4 ? rc : polygon_centroid(receiver);
  return std::max(0.0, point_to_polygon(x, newell_normal(receiver).normalized(), source, kLambertSumOnly));
}

}  // namespace hrad
