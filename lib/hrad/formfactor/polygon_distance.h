// Euclidean distance between two planar polygons in 3D (as closed point sets).
#pragma once

#include <span>

#include "hrad/core/types.h"

namespace hrad::detail {

/// Smallest distance between points of the two polygons (with their interiors). Assumes neither
/// polygon pierces the other's interior (true after mutual clipping to the front half-spaces):
/// then the minimum is attained between a vertex and a polygon or between two edges.
double polygon_distance(std::span<const Vec3> a, const Vec3& a_normal, std::span<const Vec3> b, const Vec3& b_normal);

}  // namespace hrad::detail
