// Differential-area-to-polygon form factor.
#pragma once

#include <span>

#include "hrad/core/types.h"

namespace hrad {

/// F from a differential area at `x` with unit normal `n` to the planar polygon `polygon`
/// (vertices counter-clockwise seen from its front; only its front emits/receives).
/// Lambert's contour formula (Nusselt; Cohen & Wallace 1993, eq. 4.x), with the polygon clipped
/// to the front half-space of the tangent plane at `x`. Returns 0 when the polygon is behind x,
/// faces away from x, or x lies in its plane.
double point_to_polygon(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon);

}  // namespace hrad
