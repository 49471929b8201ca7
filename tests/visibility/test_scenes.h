// Small scenes built in code for the visibility tests.
#pragma once

#include <initializer_list>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/geometry/polygon.h"

namespace hrad::test {

/// A scene with one grey material and no emitter; add patches with add_patch().
inline Scene empty_scene() {
  Scene s;
  s.path = "<test>";
  Material m;
  m.name = "grey";
  m.reflectance = Rgb::Constant(0.5);
  s.materials.push_back(m);
  return s;
}

/// Appends a patch (counter-clockwise seen from its front) and returns its index.
inline int add_patch(Scene& s, std::vector<Vec3> vertices) {
  Patch p;
  p.vertices = std::move(vertices);
  const Vec3 n = newell_normal(p.vertices);
  p.normal = n.normalized();
  p.area = 0.5 * n.norm();
  p.material = 0;
  p.face = static_cast<int>(s.faces.size());
  InputFace f;
  f.material = 0;
  f.area = p.area;
  f.patches.push_back(static_cast<int>(s.patches.size()));
  s.faces.push_back(f);
  s.patches.push_back(std::move(p));
  return static_cast<int>(s.patches.size()) - 1;
}

/// Axis-aligned square [x0, x1] x [y0, y1] at height z, front facing +z (up) or -z (down).
inline std::vector<Vec3> square_z(double x0, double x1, double y0, double y1, double z, bool up) {
  if (up) return {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
  return {{x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}};
}

}  // namespace hrad::test
