// Differential-area-to-polygon form factor.
#pragma once

#include <cmath>
#include <span>

#include "hrad/core/types.h"

namespace hrad {

/// The default accuracy of point_to_polygon(): relative, where the factor is above ~1e-300.
inline constexpr double kPointToPolygonTolerance = 1e-13;
/// `rel_tol` for the plain Lambert sum, never refined (see point_to_polygon()).
inline constexpr double kLambertSumOnly = INFINITY;

/// F from a differential area at `x` with unit normal `n` to the planar polygon `polygon`
/// (vertices counter-clockwise seen from its front; only its front emits/receives).
/// Lambert's contour formula (Nusselt; Cohen & Wallace 1993, eq. 4.16), with the polygon clipped
/// to the front half-space of the tangent plane at `x`. Returns 0 when the polygon is behind x,
/// faces away from x, or x lies in its plane.
///
/// The contour sum cancels where the factor is small against its terms (polygons small, thin or far
/// against their distance, or grazing the tangent plane); where its rounding bound exceeds
/// `rel_tol` times the result, the polygon is refined (see the .cpp). `rel_tol = kLambertSumOnly`
/// returns the plain sum, with an absolute error up to ~1e-16 times the sum of its terms: cheaper
/// where it cancels, and each point's factors to a closed surface still sum to 1 to rounding (the
/// solvers' point-contour kernel). Usage:
///   double f = point_to_polygon(x, n, quad);                   // ~1e-13 relative
///   double g = point_to_polygon(x, n, quad, kLambertSumOnly);  // ~1e-16 absolute
double point_to_polygon(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon,
                        double rel_tol = kPointToPolygonTolerance);

}  // namespace hrad
