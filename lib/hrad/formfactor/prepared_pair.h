// The common first step of the polygon-to-polygon kernels: local, scaled coordinates and the
// mutual clipping of the two polygons to each other's front half-space.
#pragma once

#include <span>
#include <vector>

#include "hrad/core/types.h"

namespace hrad::detail {

struct PreparedPair {
  std::vector<Vec3> from, to;   // clipped, in local coordinates (x - origin) / scale
  Vec3 from_normal, to_normal;  // unit normals (fronts)
  double from_area = 0.0;       // areas of the unclipped input polygons, in input units^2
  double to_area = 0.0;
  double scale = 1.0;    // input length per local length
  bool visible = false;  // false: the factor is exactly 0 (facing away, coplanar, behind, degenerate)
};

/// Prepares the pair; `visible` is false when either clipped polygon has no area.
PreparedPair prepare_pair(std::span<const Vec3> from, std::span<const Vec3> to);

}  // namespace hrad::detail
