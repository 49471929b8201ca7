// Polygon-to-polygon form factor, closed form.
#pragma once

#include <span>

#include "hrad/core/types.h"

namespace hrad {

/// The default accuracy of polygon_to_polygon(): a contour sum is accepted when its rounding bound
/// is within this of the result, otherwise the pair is refined (see the .cpp).
inline constexpr double kPolygonToPolygonTolerance = 1e-11;

/// Both directions of one evaluation; area(from) * from_to == area(to) * to_from to rounding.
struct PairFormFactor {
  double from_to = 0.0;
  double to_from = 0.0;
};

/// Form factors between two planar convex-or-not simple polygons (vertices counter-clockwise
/// seen from each front). Each polygon is clipped to the front half-space of the other; a pair
/// facing away or coplanar gives exactly 0. Singular configurations (shared edges and vertices,
/// collinear and parallel edges, touching polygons) are handled by their exact limits; far-apart
/// pairs switch to quadrature where the closed form would cancel. Unit-independent.
///
/// `rel_tol` is the relative accuracy asked for (default kPolygonToPolygonTolerance, ~1e-11 and
/// better: the tests hold it to Howell's closed forms). A solver that needs less (its
/// discretisation error is many orders larger) passes a looser one: far pairs then take lower
/// Gauss orders and closer pairs keep their contour sum (FormFactorEvaluator uses 1e-9).
///
/// `abs_tol` (default 0) is an absolute accuracy in factor units that is enough too: a pair that
/// barely sees itself (one polygon grazing the other's plane, leaving slivers after clipping) has a
/// factor of 1e-12 whose contour sum cancels; at 1e-7 relative its refinement takes a fraction of a
/// second, while a solver needs it only to ~1e-9 of the smaller area.
PairFormFactor polygon_to_polygon(std::span<const Vec3> from, std::span<const Vec3> to,
                                  double rel_tol = kPolygonToPolygonTolerance, double abs_tol = 0.0);

}  // namespace hrad
