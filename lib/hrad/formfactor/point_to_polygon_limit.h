// Differential-area-to-polygon factor at a point approached from inside its element: the one-sided
// limit where the point lies in the polygon's plane (a point on an edge shared with the polygon, or
// where its element touches the polygon), which point_to_polygon() counts as 0.
#pragma once

#include <span>

#include "hrad/core/types.h"
#include "hrad/formfactor/point_to_polygon.h"

namespace hrad {

/// lim_{t -> 0+} F(dA_{x + t d} -> polygon) with x's unit normal n and a direction d in x's tangent
/// plane (towards the inside of the element x belongs to); F as point_to_polygon(). Where x lies
/// strictly in front of the polygon's plane (by more than 1e-12 of its distance to the nearest
/// vertex) the factor is continuous and point_to_polygon() gives it. Otherwise Lambert's contour
/// formula is taken to the limit term by term (Cohen & Wallace 1993, eq. 4.16), with the polygon
/// first clipped to x's front half-space: for an edge whose line holds x, strictly inside the edge
/// the angle is pi and the edge's plane through x' tends to the one spanned by the edge and d; a
/// vertex at x is seen in direction -d. The polygon seen edge-on from x, as from a point on an edge
/// shared with it, then counts with the part of x's hemisphere it fills in the limit (1/2 for a
/// perpendicular polygon across the whole hemisphere's edge). `rel_tol` is point_to_polygon()'s
/// for the point strictly in front (kLambertSumOnly: the plain sum, ~1e-16 absolute).
double point_to_polygon_limit(const Vec3& x, const Vec3& n, const Vec3& d, std::span<const Vec3> polygon,
                              double rel_tol = kPointToPolygonTolerance);

}  // namespace hrad
