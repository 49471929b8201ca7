// Polygon-to-polygon form factor, closed form.
#pragma once

#include <span>

#include "hrad/core/types.h"

namespace hrad {

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
PairFormFactor polygon_to_polygon(std::span<const Vec3> from, std::span<const Vec3> to);

}  // namespace hrad
