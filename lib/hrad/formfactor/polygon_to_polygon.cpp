// Polygon to polygon (first version: Gauss quadrature over `from` of the exact point-to-polygon
// factor; replaced by the contour-integral closed form below).
#include "hrad/formfactor/polygon_to_polygon.h"

#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/formfactor/polygon_quadrature.h"
#include "hrad/formfactor/prepared_pair.h"

namespace hrad {

PairFormFactor polygon_to_polygon(std::span<const Vec3> from, std::span<const Vec3> to) {
  const detail::PreparedPair pair = detail::prepare_pair(from, to);
  if (!pair.visible) return {};
  thread_local std::vector<detail::WeightedPoint> points;
  points.clear();
  detail::polygon_quadrature(pair.from, pair.from_normal, 24, points);
  double area_factor = 0.0;  // A_from F_from_to in local units
  for (const auto& p : points) area_factor += p.weight * point_to_polygon(p.x, pair.from_normal, pair.to);
  area_factor *= pair.scale * pair.scale;
  return {area_factor / pair.from_area, area_factor / pair.to_area};
}

}  // namespace hrad
