// Sutherland-Hodgman clipping of a polygon to a half-space given by signed vertex distances.
#pragma once

#include <span>
#include <vector>

#include "hrad/core/types.h"

namespace hrad::detail {

/// Keeps the part of `polygon` where the (affine) signed distance is >= 0; `distance[i]` is the
/// signed distance of vertex i. Vertices with distance exactly 0 are kept as they are, so an edge
/// lying in the clipping plane survives unchanged. Writes the result (possibly empty) to `out`.
/// (Sutherland & Hodgman 1974.)
void clip_to_half_space(std::span<const Vec3> polygon, std::span<const double> distance, std::vector<Vec3>& out);

}  // namespace hrad::detail
