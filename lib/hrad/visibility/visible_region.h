// Exact from-point visibility: the part of a source polygon that a point sees.
#pragma once

#include <span>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"

namespace hrad {

/// A planar polygon with holes, in 3D.
struct PolygonWithHoles3 {
  std::vector<Vec3> outer;               ///< counter-clockwise seen from the source's front
  std::vector<std::vector<Vec3>> holes;  ///< clockwise seen from the source's front
};

struct VisibleRegion {
  std::vector<PolygonWithHoles3> pieces;  ///< vertices rounded to double once, at the end
  double area_fraction = 0.0;             ///< visible area / source area, from exact areas, rounded once
};

/// The part of the convex planar polygon `source` (on patch `source_patch`, counter-clockwise seen
/// from its front) that the point `x` (on patch `patch_x`, or -1) sees past the scene's other
/// patches, under the rules of segment_blocked(): the occluders (every patch except the two named)
/// are clipped to the pyramid from x over the source, projected from x onto the source's plane and
/// subtracted with CGAL's 2D Boolean operations, all in exact rational arithmetic
/// (Exact_predicates_exact_constructions_kernel). Empty when x is not strictly in front of the
/// source. Patches in the source's plane or through x project to zero area and are skipped.
/// Cost: milliseconds per call; a reference, not a solver kernel.
VisibleRegion visible_region(const Scene& scene, const Vec3& x, int patch_x, std::span<const Vec3> source,
                             int source_patch);

}  // namespace hrad
