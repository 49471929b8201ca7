// A_from * F_from_to by the double contour integral (Stokes' theorem twice on the area-area
// integral; Sparrow 1963; Schroeder & Hanrahan 1993, eq. 3):
//   A_i F_ij = 1/(2 pi) sum_p sum_q (a_p . b_q) int_{edge p} int_{edge q} ln r ds dt.
#pragma once

#include <span>

#include "hrad/core/types.h"

namespace hrad::detail {

struct ContourSum {
  double area_factor = 0.0;  // A_from F_from_to, in the polygons' length unit squared
  double magnitude = 0.0;    // sum of the terms' absolute sizes: rounding error ~ eps * magnitude
};

/// The double contour sum over the edges of two polygons that already lie in each other's front
/// half-space. It cancels when the result is small against the edge terms (far or sliver pairs):
/// `magnitude` says by how much.
ContourSum contour_area_factor(std::span<const Vec3> from, std::span<const Vec3> to);

}  // namespace hrad::detail
