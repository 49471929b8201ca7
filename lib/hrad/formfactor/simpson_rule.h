// The corner, edge-midpoint and centre points of an element with quadrature weights: the points at
// which the hierarchical solver's oracle samples point-to-polygon factors. They are the corners of
// the element's four children under ElementHierarchy's 1-to-4 splits, so a child's corners are
// its parent's points.
#pragma once

#include <array>
#include <span>

#include "hrad/core/types.h"

namespace hrad {

/// Where simpson_points() lie on a quad: (u, v) of each on the bilinear map
/// x = (1-u)(1-v) v0 + u(1-v) v1 + uv v2 + (1-u)v v3.
inline constexpr double kSimpsonQuadUv[9][2] = {{0, 0},   {1, 0},   {1, 1},   {0, 1},    {0.5, 0},
                                                {1, 0.5}, {0.5, 1}, {0, 0.5}, {0.5, 0.5}};
/// The point at (u, v) of the bilinear map of the quad (4 vertices) above.
inline Vec3 bilinear_point(std::span<const Vec3> quad, double u, double v) {
  return (1 - u) * (1 - v) * quad[0] + u * (1 - v) * quad[1] + u * v * quad[2] + (1 - u) * v * quad[3];
}
/// Where simpson_points() lie on a triangle: barycentric coordinates of each.
inline constexpr double kSimpsonTriangleBary[7][3] = {
    {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}, {1.0 / 3, 1.0 / 3, 1.0 / 3}};

/// At most 9 points: a quad gives 9, a triangle 7.
struct SimpsonPoints {
  std::array<Vec3, 9> x{};
  std::array<double, 9> weight{};  ///< area elements: they sum to the element's area
  int count = 0;
};

/// Points of a convex planar triangle or quad, counter-clockwise: vertices 0..k-1, then the
/// midpoint of each edge (edge i runs from vertex i to vertex i + 1), then the centre.
///  * Quad: the tensor Simpson rule on the bilinear map x(u, v) (weights (1, 4, 1) x (1, 4, 1) / 36
///    times the Jacobian |x_u x x_v| at the point), exact for bicubic integrands; the centre is
///    x(1/2, 1/2), the vertex mean, as in the 1-to-4 split.
///  * Triangle: the 7-point rule with weights 1/20 (vertices), 2/15 (midpoints) and 9/20 (centroid)
///    of the area, exact for cubics (Stroud 1971, T2:3-1).
SimpsonPoints simpson_points(std::span<const Vec3> polygon);

/// The mean over the element of the linear field (bilinear on a quad's map) through values at its
/// corners, as weights of the corner values (they sum to 1): from the points' quadrature, which is
/// exact for it. A parallelogram's are 1/4 each, a triangle's 1/3.
std::array<double, 4> corner_mean_weights(const SimpsonPoints& points);

/// Indices into the parent's simpson_points() of child k's corners, in the child's vertex order,
/// for ElementHierarchy::split() of a quad (4 vertices) or a triangle.
std::array<int, 4> child_corner_points(int vertex_count, int child);

}  // namespace hrad
