#include "hrad/solvers/linear_basis.h"

#include <Eigen/Dense>

namespace hrad {

double linear_function(int vertex_count, int corner, int point) {
  if (vertex_count == 4) {
    const double u = kSimpsonQuadUv[point][0], v = kSimpsonQuadUv[point][1];
    const double cu = kSimpsonQuadUv[corner][0], cv = kSimpsonQuadUv[corner][1];
    return (cu > 0.5 ? u : 1.0 - u) * (cv > 0.5 ? v : 1.0 - v);
  }
  return kSimpsonTriangleBary[point][corner];
}

LinearProjection linear_projection(const SimpsonPoints& s) {
  const int vertex_count = s.count == 9 ? 4 : 3;
  const int n = linear_corners(vertex_count);
  // Mass matrix M_ab = sum_k w_k psi_a(x_k) psi_b(x_k) and right-hand side r_a = sum_k w_k psi_a(x_k) f_k:
  // corner values c = M^-1 R f.
  Eigen::Matrix4d mass = Eigen::Matrix4d::Identity();
  Eigen::Matrix<double, 4, 9> rhs = Eigen::Matrix<double, 4, 9>::Zero();
  for (int a = 0; a < n; ++a)
    for (int k = 0; k < s.count; ++k)
      rhs(a, k) = s.weight[static_cast<std::size_t>(k)] * linear_function(vertex_count, a, k);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      double m = 0.0;
      for (int k = 0; k < s.count; ++k) m += rhs(a, k) * linear_function(vertex_count, b, k);
      mass(a, b) = m;
    }
  LinearProjection p;
  double area = 0.0;
  for (int k = 0; k < s.count; ++k) area += s.weight[static_cast<std::size_t>(k)];
  if (!(area > 0.0)) {
    // A degenerate element: its corners take the plain mean of its points.
    for (int a = 0; a < n; ++a)
      for (int k = 0; k < s.count; ++k)
        p.weight[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)] = 1.0 / s.count;
    return p;
  }
  const Eigen::Matrix<double, 4, 9> w = mass.ldlt().solve(rhs);
  for (int a = 0; a < n; ++a)
    for (int k = 0; k < s.count; ++k) p.weight[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)] = w(a, k);
  return p;
}

PointValues project_linear(const LinearProjection& projection, int vertex_count, const PointValues& values) {
  const int n = linear_corners(vertex_count), points = vertex_count == 4 ? 9 : 7;
  std::array<Rgb, 4> corner;
  for (int a = 0; a < n; ++a) {
    corner[static_cast<std::size_t>(a)] = Rgb::Zero();
    for (int k = 0; k < points; ++k)
      corner[static_cast<std::size_t>(a)] +=
          projection.weight[static_cast<std::size_t>(a)][static_cast<std::size_t>(k)] *
          values[static_cast<std::size_t>(k)];
  }
  PointValues out;
  out.fill(Rgb::Zero());
  for (int k = 0; k < points; ++k)
    for (int a = 0; a < n; ++a)
      out[static_cast<std::size_t>(k)] += linear_function(vertex_count, a, k) * corner[static_cast<std::size_t>(a)];
  return out;
}

PointValues point_field_moments(const std::array<double, 9>& weight, int count, const PointValues& values) {
  // Quads: the biquadratic Lagrange function phi_i is 1 at point i and 0 at the others, so the
  // Simpson rule gives w_i B_i. Triangles: the quadratic vertex functions are -1/9 at the
  // centroid, the midpoint functions 4/9.
  PointValues m;
  m.fill(Rgb::Zero());
  if (count == 9) {
    for (std::size_t i = 0; i < 9; ++i) m[i] = weight[i] * values[i];
    return m;
  }
  const Rgb centre = weight[6] * values[6];
  for (std::size_t i = 0; i < 3; ++i) m[i] = weight[i] * values[i] - centre / 9.0;
  for (std::size_t i = 3; i < 6; ++i) m[i] = weight[i] * values[i] + centre * (4.0 / 9.0);
  return m;
}

std::array<double, 9> basis_integrals(const SimpsonPoints& points, double area) {
  std::array<double, 9> b{};
  if (points.count == 9) return points.weight;
  for (int m = 3; m < 6; ++m) b[static_cast<std::size_t>(m)] = area / 3.0;
  return b;
}

std::array<double, 9> bernstein_weighting(const std::array<double, 9>& f, int count) {
  std::array<double, 9> g = f;
  const int corners = count == 9 ? 4 : 3;
  for (int e = 0; e < corners; ++e)
    g[static_cast<std::size_t>(corners + e)] =
        0.25 * (f[static_cast<std::size_t>(e)] + f[static_cast<std::size_t>((e + 1) % corners)]) +
        0.5 * f[static_cast<std::size_t>(corners + e)];
  if (count == 9) {
    double centre = 0.25 * f[8];
    for (int k = 0; k < 4; ++k)
      centre += f[static_cast<std::size_t>(k)] / 16.0 + f[static_cast<std::size_t>(4 + k)] / 8.0;
    g[8] = centre;
  } else {
    g[6] = 0.0;  // a triangle's 7th point is not a basis function
  }
  return g;
}

}  // namespace hrad
