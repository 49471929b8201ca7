// Gauss points on a planar polygon: ear-clipping triangulation, then the collapsed (Duffy) product
// Gauss-Legendre rule on each triangle (Stroud 1971, sec. 2.7; Duffy 1982).
#pragma once

#include <span>
#include <vector>

#include "hrad/core/types.h"

namespace hrad::detail {

struct WeightedPoint {
  Vec3 x;
  double weight;  // area element: the weights of one polygon sum to its area
};

/// Appends order^2 points per triangle of `polygon` to `out`; integrates polynomials of degree
/// 2*order-2 over each triangle exactly.
void polygon_quadrature(std::span<const Vec3> polygon, const Vec3& unit_normal, int order,
                        std::vector<WeightedPoint>& out);

/// The same rule on the triangle (a, b, c).
void triangle_quadrature(const Vec3& a, const Vec3& b, const Vec3& c, int order, std::vector<WeightedPoint>& out);

}  // namespace hrad::detail
