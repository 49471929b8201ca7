// Linear elements: the radiosity over each leaf is linear on a triangle and bilinear on a quad's
// map x(u, v), discontinuous between leaves, given by its values at the element's corners
// (Heckbert & Winget 1991, "Finite element methods for global illumination": nodal linear bases;
// Zatz 1993, "Galerkin radiosity: a higher order solution method for global illumination": the
// radiosity as a projection onto a polynomial basis per element; Gortler, Schroeder, Cohen & Hanrahan 1993, "Wavelet
// radiosity": the same projection on a hierarchy, with the two-scale relations carrying it between levels).
//
// The design keeps one gather. Every link operator already delivers a leaf's irradiance H as a
// field of values at its simpson_points() (biquadratic on a quad, quadratic on a triangle:
// link_operator.h PointValues), and reads a source's radiosity through its moments against that
// basis (NodeField::radiosity_moments), which push-pull pulls up the hierarchy exactly. A linear
// field lies in that point basis, so the linear basis changes only what a leaf does with its
// gathered field (push_pull.h):
//  * B = P (E + rho H): the L2 projection onto the linear space over the element, with the element's
//    own Simpson quadrature as the inner product (exact for the linear mass matrix on triangles and
//    parallelograms). Projection keeps the element's mean (constants lie in the space), so power is
//    conserved as with constant elements, and a uniform field is reproduced exactly. The error of
//    the projection of a smooth field is O(h^2) (Schroeder & Hanrahan 1994, "Wavelet methods for
//    radiance computations": piecewise linear is the practical sweet spot), against O(h) for the
//    element mean.
//  * The moments a link reads are integral phi_i B over the element, by the same quadrature: exact
//    for a linear B on triangles and parallelograms (phi_i B is cubic there).
//  * Jacobi iterates on the corner values; a step's change is the largest change of B at the points.
// Links carry the factor's shape over both ends (refinement_oracle.h: the point factors at the
// receiver's points, exact point-to-polygon factors from the same evaluator, and the source's
// shape towards the receiver), so the hierarchical solver needs no new factors. The full matrix
// and substructuring gather through field links of the same kind, with each receiver point's exact
// factor (field_links.h).
#pragma once

#include <array>

#include "hrad/formfactor/simpson_rule.h"
#include "hrad/solvers/link_operator.h"

namespace hrad {

/// The integrals over an element of the basis functions of PointValues fields, against which
/// NodeField::radiosity_moments are taken: a quad's biquadratic functions integrate to its Simpson
/// weights, a triangle's quadratic ones to 0 at the vertices and a third of the area at the
/// midpoints (6 functions).
std::array<double, 9> basis_integrals(const SimpsonPoints& points, double area);
/// The number of basis functions of PointValues fields (9 on a quad, 6 on a triangle).
inline int basis_functions(const SimpsonPoints& points) { return points.count == 9 ? 9 : 6; }

/// A source's weighting of its own radiosity, sum_i G_i m_i over its moments = the integral of g B,
/// from point samples f >= 0 of the kernel towards a receiver (at the simpson_points(); `count` 9 or
/// 7): G are the values at the points of the quadratic (biquadratic) Bernstein polynomial whose
/// control values are f (vertices keep f; an edge midpoint takes (f_a + 2 f_m + f_b) / 4; a quad's
/// centre the tensor product of that). That g is >= 0 everywhere, so the weighting is an average of B
/// and cannot overshoot: the interpolant through f instead dips below 0 between the points of a
/// kernel peaked near one edge (a large source beside a small receiver) and then sends a radiosity
/// far outside the source's range, even negative (Farin 2002, "Curves and surfaces for CAGD", ch. 3:
/// the Bernstein form's positivity and variation diminishing).
std::array<double, 9> bernstein_weighting(const std::array<double, 9>& f, int count);

/// A triangle's quadratic through its values at the vertices and edge midpoints (PointValues order),
/// at the centroid: -1/9 of each vertex value, 4/9 of each midpoint value.
template <typename Values>
double triangle_quadratic_centre(const Values& f) {
  double c = 0.0;
  for (int i = 0; i < 3; ++i)
    c += -f[static_cast<std::size_t>(i)] / 9.0 + 4.0 * f[static_cast<std::size_t>(3 + i)] / 9.0;
  return c;
}

/// Corners of an element with `vertex_count` vertices (3 or 4): the linear basis's functions.
inline int linear_corners(int vertex_count) { return vertex_count == 4 ? 4 : 3; }

/// The nodal linear function of `corner` at simpson point `point` (bilinear in (u, v) on a quad,
/// barycentric on a triangle).
double linear_function(int vertex_count, int corner, int point);

/// The L2 projection of a PointValues field onto an element's linear space: corner value a is
/// sum_k weight[a][k] value_k over the element's simpson_points().
struct LinearProjection {
  std::array<std::array<double, 9>, 4> weight{};
};

/// The projection for an element with these points (`points.count` 9: quad, 7: triangle).
LinearProjection linear_projection(const SimpsonPoints& points);

/// Projects point values (E + rho H at the points) onto the linear space and returns the linear
/// field's values at the same points (unused points 0).
PointValues project_linear(const LinearProjection& projection, int vertex_count, const PointValues& values);

/// The moments integral phi_i B (link_operator.h NodeField::radiosity_moments) of the field given
/// by its values at the points, by the element's Simpson quadrature (`weight`, `count`: SimpsonPoints).
PointValues point_field_moments(const std::array<double, 9>& weight, int count, const PointValues& values);

}  // namespace hrad
