// A scene of polygons for the mesh tests.
#pragma once

#include <vector>

#include "hrad/core/scene.h"
#include "hrad/geometry/polygon.h"

namespace hrad::test {

/// A scene of the given polygons (each CCW about its normal), one white material.
inline Scene make_scene(const std::vector<std::vector<Vec3>>& polygons) {
  Scene s;
  s.materials.push_back({"white", Rgb::Constant(0.5), Rgb::Zero()});
  for (const auto& poly : polygons) {
    Patch p;
    p.vertices = poly;
    p.normal = newell_normal(poly).normalized();
    p.area = polygon_area(poly);
    p.material = 0;
    p.face = static_cast<int>(s.faces.size());
    s.patches.push_back(p);
    s.faces.push_back({"g", 0, 0, p.area, {p.face}});
  }
  return s;
}

}  // namespace hrad::test
