#include "hrad/visibility/occluded_form_factor.h"

#include <algorithm>
#include <vector>

#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/visibility/visible_region.h"

namespace hrad {

double occluded_point_to_polygon(const Scene& scene, const Vec3& x, const Vec3& n, int patch_x,
                                 std::span<const Vec3> source, int source_patch) {
  const VisibleRegion region = visible_region(scene, x, patch_x, source, source_patch);
  double f = 0.0;
  for (const PolygonWithHoles3& piece : region.pieces) {
    f += point_to_polygon(x, n, piece.outer);
    for (std::vector<Vec3> hole : piece.holes) {
      std::reverse(hole.begin(), hole.end());  // counter-clockwise, as point_to_polygon expects
      f -= point_to_polygon(x, n, hole);
    }
  }
  return f;
}

}  // namespace hrad
