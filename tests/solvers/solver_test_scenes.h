// Small scenes built in code for the solver tests: closed boxes (optionally with T-junctions and an
// occluding block), faceted spheres, scaling.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/geometry/polygon.h"

namespace hrad::test {

/// Adds a planar convex polygon, reversed if needed so that its front faces `towards`.
inline void add_polygon(Scene& s, std::vector<Vec3> poly, const Vec3& towards, int material) {
  if (newell_normal(poly).dot(towards) < 0.0) std::reverse(poly.begin(), poly.end());
  Patch p;
  p.vertices = poly;
  p.normal = newell_normal(poly).normalized();
  p.area = polygon_area(poly);
  p.material = material;
  p.face = static_cast<int>(s.faces.size());
  p.group = "f" + std::to_string(p.face);
  s.faces.push_back({p.group, material, 0, p.area, {static_cast<int>(s.patches.size())}});
  s.patches.push_back(p);
}

inline Material material(const Rgb& rho, const Rgb& e, const std::string& name = "m") { return {name, rho, e}; }

/// The inward-facing walls of the box [0,a] x [0,b] x [0,c]; wall k (floor, ceiling, x=0, x=a,
/// z=0, z=c) uses material wall_material[k]. With `t_junctions`, the floor is cut into two
/// halves and the x = 0 wall into three strips, so that the walls meet in T-junctions.
inline Scene make_box(double a, double b, double c, std::vector<Material> materials, std::vector<int> wall_material,
                      bool t_junctions = false) {
  Scene s;
  s.materials = std::move(materials);
  const Vec3 centre(a / 2, b / 2, c / 2);
  auto wall = [&](std::vector<Vec3> v, int k) {
    add_polygon(s, v, centre - polygon_centroid(v), wall_material[static_cast<std::size_t>(k)]);
  };
  if (t_junctions) {
    wall({{0, 0, 0}, {a / 2, 0, 0}, {a / 2, 0, c}, {0, 0, c}}, 0);
    wall({{a / 2, 0, 0}, {a, 0, 0}, {a, 0, c}, {a / 2, 0, c}}, 0);
  } else {
    wall({{0, 0, 0}, {a, 0, 0}, {a, 0, c}, {0, 0, c}}, 0);
  }
  wall({{0, b, 0}, {a, b, 0}, {a, b, c}, {0, b, c}}, 1);
  if (t_junctions) {
    for (int k = 0; k < 3; ++k)
      wall({{0, b * k / 3, 0}, {0, b * (k + 1) / 3, 0}, {0, b * (k + 1) / 3, c}, {0, b * k / 3, c}}, 2);
  } else {
    wall({{0, 0, 0}, {0, b, 0}, {0, b, c}, {0, 0, c}}, 2);
  }
  wall({{a, 0, 0}, {a, b, 0}, {a, b, c}, {a, 0, c}}, 3);
  wall({{0, 0, 0}, {a, 0, 0}, {a, b, 0}, {0, b, 0}}, 4);
  wall({{0, 0, c}, {a, 0, c}, {a, b, c}, {0, b, c}}, 5);
  return s;
}

/// Adds the faces (outward) of the block [x0,x1] x [y0,y1] x [z0,z1]; its bottom face only when it
/// floats (y0 > 0), so that a block standing on the floor does not overlap it.
inline void add_block(Scene& s, double x0, double x1, double y0, double y1, double z0, double z1, int material) {
  const Vec3 c((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2);
  auto face = [&](std::vector<Vec3> v) { add_polygon(s, v, polygon_centroid(v) - c, material); };
  face({{x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}});
  if (y0 > 0) face({{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}});
  face({{x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}});
  face({{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}});
  face({{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}});
  face({{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}});
}

/// A sphere of radius r faceted by `rings` latitude bands and `sectors` longitudes (triangles at
/// the poles, planar isosceles trapezoids between), facing the centre; the top cap uses material 1,
/// the rest material 0.
inline Scene make_faceted_sphere(double r, int rings, int sectors, const Material& wall, const Material& cap) {
  Scene s;
  s.materials = {wall, cap};
  auto point = [&](int i, int j) {
    const double theta = std::numbers::pi * i / rings;
    const double phi = 2 * std::numbers::pi * j / sectors;
    return Vec3(r * std::sin(theta) * std::cos(phi), r * std::cos(theta), r * std::sin(theta) * std::sin(phi));
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      std::vector<Vec3> v;
      if (i == 0)
        v = {point(0, 0), point(1, j), point(1, j + 1)};
      else if (i == rings - 1)
        v = {point(i, j), point(i, j + 1), point(rings, 0)};
      else
        v = {point(i, j), point(i, j + 1), point(i + 1, j + 1), point(i + 1, j)};
      add_polygon(s, v, -polygon_centroid(v), i == 0 ? 1 : 0);
    }
  return s;
}

/// Every coordinate times `factor`.
inline Scene scaled(Scene s, double factor) {
  for (Patch& p : s.patches) {
    for (Vec3& v : p.vertices) v *= factor;
    p.area = polygon_area(p.vertices);
  }
  for (InputFace& f : s.faces) f.area *= factor * factor;
  return s;
}

// Largest per-face, per-channel difference between two solutions of `s` (a face's radiosity is
// the area mean of its patches, as `hrad solve` reports it), relative to the brighter of `ref`'s
// and its area-mean reflected radiosity (emitters skipped); and the ratio of their total powers.
struct Agreement {
  double largest = 0.0, power_ratio = 0.0;
};
inline Agreement face_agreement(const Scene& s, const Solution& ref, const Solution& other) {
  double mean_reflected = 0.0, power_ref = 0.0, power_other = 0.0;
  std::vector<Rgb> face_ref(s.faces.size(), Rgb::Zero()), face_other(s.faces.size(), Rgb::Zero());
  std::vector<double> face_area(s.faces.size(), 0.0);
  std::vector<bool> emits(s.faces.size(), false);
  for (std::size_t i = 0; i < s.patches.size(); ++i) {
    const Patch& p = s.patches[i];
    const Material& m = s.material_of(p);
    const auto f = static_cast<std::size_t>(p.face);
    mean_reflected += p.area * (ref.patch_radiosity[i] - m.emission).mean() / s.total_area();
    power_ref += p.area * ref.patch_radiosity[i].mean();
    power_other += p.area * other.patch_radiosity[i].mean();
    face_ref[f] += p.area * ref.patch_radiosity[i];
    face_other[f] += p.area * other.patch_radiosity[i];
    face_area[f] += p.area;
    emits[f] = m.is_emitter();
  }
  Agreement a;
  a.power_ratio = power_other / power_ref;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (emits[f] || !(face_area[f] > 0.0)) continue;
    for (int c = 0; c < 3; ++c) {
      const double r = face_ref[f][c] / face_area[f];
      a.largest = std::max(a.largest, std::abs(face_other[f][c] / face_area[f] - r) / std::max(r, mean_reflected));
    }
  }
  return a;
}

}  // namespace hrad::test
