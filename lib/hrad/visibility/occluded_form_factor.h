// The exact occluded point-to-polygon form factor: the reference for sampled visibility.
#pragma once

#include <span>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"

namespace hrad {

/// Form factor from a differential area at `x` (unit normal `n`, on patch `patch_x` or -1) to the
/// part of the convex polygon `source` (on patch `source_patch`) that x sees: the unoccluded
/// point-to-polygon factor (Lambert's contour formula, hrad/formfactor/point_to_polygon.h) of each
/// piece of visible_region(), minus that of its holes (the kernel integrates over area, so it is
/// additive over the pieces).
double occluded_point_to_polygon(const Scene& scene, const Vec3& x, const Vec3& n, int patch_x,
                                 std::span<const Vec3> source, int source_patch);

}  // namespace hrad
