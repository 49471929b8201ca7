// Factors from points to surfaces, obstructed: F(dA_x -> u) for a point x with unit normal n (a
// mean-radiant-temperature probe, a sensor) to every unit u of a scene, exact:
//   Lambert's contour formula (point_to_polygon(), ~1e-13) to each patch classified fully visible
//   from x (shaft culling with exact predicates), 0 to fully hidden ones, and Lambert's formula to
//   the exact visible region (visible_region(): exact rational arithmetic, milliseconds) of partly
//   visible ones. 1 - sum_u F is what the point sees of the sky (or of obstruction-only surfaces).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "hrad/core/probe_point.h"
#include "hrad/core/progress.h"
#include "hrad/core/scene.h"
#include "hrad/viewfactors/surface_units.h"
#include "hrad/visibility/visible_region.h"

namespace hrad {

struct PointFactors {
  int points = 0, units = 0;
  std::vector<double> factor;                          ///< points x units, row-major: F(point i -> unit u)
  std::uint64_t visible = 0, hidden = 0, partial = 0;  ///< point-patch pairs by class (front-facing ones)

  double at(int i, int u) const {
    return factor[static_cast<std::size_t>(i) * static_cast<std::size_t>(units) + static_cast<std::size_t>(u)];
  }
};

PointFactors point_view_factors(const Scene& scene, const SurfaceUnits& units, std::span<const ProbePoint> points,
                                int threads = 0, const ProgressSink& progress = {});

/// F(dA_x -> region) by Lambert's formula: each piece's outer contour minus its holes.
double point_factor_to_region(const Vec3& x, const Vec3& n, const VisibleRegion& region);

}  // namespace hrad
