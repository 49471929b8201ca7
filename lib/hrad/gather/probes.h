// Light at a lighting designer's probe points by final gather (final_gather.h): the irradiance
// H(x) = sum_j F(x -> j) V(x, j) B_j a sensor at x facing n receives from the solution's leaves
// (exitance units: lux when the scene's emission is luminous exitance in lm/m^2), and, for a point
// on a patch's front (geometry/front_patch.h), that patch's radiosity B = E + rho H. A point need not
// lie on a surface: a point in space is classified against every patch from the point itself.
//
// Work-plane grids (illuminance tables on a desk or floor plane; e.g. EN 12464-1's task areas):
// the centres of an nu x nv grid of cells over a rectangle in a plane x, y or z = height, every
// point facing the same way along that axis.
#pragma once

#include <span>
#include <vector>

#include "hrad/core/probe_point.h"
#include "hrad/core/progress.h"
#include "hrad/gather/final_gather.h"

namespace hrad {

struct ProbeValue {
  int patch = -1;                ///< the patch whose front the point lies on, or -1 (a point in space)
  Rgb irradiance = Rgb::Zero();  ///< H at the point facing its normal
  Rgb radiosity = Rgb::Zero();   ///< E + rho H of that patch (0 when patch is -1)
};

/// The value at each probe, in parallel and deterministically (final_gather.h). A point found on a
/// patch's front (front_patch_at with probe_tolerance) is moved onto the patch's plane and faces
/// its normal, as hrad reference does, so the two answer the same question.
std::vector<ProbeValue> gather_probes(const FinalGather& gather, std::span<const ProbePoint> points,
                                      ProgressReporter* progress = nullptr);

/// A rectangle of probe points in the plane `axis` = height (axis 0, 1, 2 for x, y, z), facing
/// +axis (facing_positive) or -axis. The rectangle runs from (u0, v0) to (u1, v1) in the two other
/// coordinates in their order (x: y, z; y: x, z; z: x, y).
struct ProbeGrid {
  int axis = 1;
  bool facing_positive = true;
  double height = 0.0;
  double u0 = 0.0, v0 = 0.0, u1 = 1.0, v1 = 1.0;
  int nu = 1, nv = 1;
};

/// The centres of the grid's nu x nv cells, u fastest: point i + nu * j at
/// u0 + (i + 1/2) (u1 - u0) / nu, v0 + (j + 1/2) (v1 - v0) / nv.
std::vector<ProbePoint> grid_points(const ProbeGrid& grid);

}  // namespace hrad
