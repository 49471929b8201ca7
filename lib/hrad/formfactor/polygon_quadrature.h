// Gauss points on a planar polygon: triangulation, each triangle cut into three quadrilaterals at its
// centroid and edge midpoints, product Gauss-Legendre on each bilinear quadrilateral. Unlike the
// collapsed (Duffy) rule this keeps the total polynomial degree: a polynomial of degree k in x is of
// degree <= k in each of u and v, so `order` points integrate total degree 2 order - 1 exactly
// (Stroud 1971, sec. 1.4 and 2.7).
#pragma once

#include <span>
#include <vector>

#include "hrad/core/types.h"

namespace hrad::detail {

struct WeightedPoint {
  Vec3 x;
  double weight;  // area element: the weights of one polygon sum to its area
};

/// Appends 3 order^2 points per triangle of `polygon` to `out`.
void polygon_quadrature(std::span<const Vec3> polygon, const Vec3& unit_normal, int order,
                        std::vector<WeightedPoint>& out);

/// The same rule on the triangle (a, b, c).
void triangle_quadrature(const Vec3& a, const Vec3& b, const Vec3& c, int order, std::vector<WeightedPoint>& out);

}  // namespace hrad::detail
