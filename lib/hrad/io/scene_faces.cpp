#include "hrad/io/scene_faces.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "hrad/geometry/polygon.h"

namespace hrad::detail {
namespace {

void add_patch(Scene& scene, int face, std::vector<Vec3> vertices) {
  Patch p;
  const Vec3 n = newell_normal(vertices);
  p.area = 0.5 * n.norm();
  p.normal = n.normalized();
  p.vertices = std::move(vertices);
  p.material = scene.faces[face].material;
  p.group = scene.faces[face].group;
  p.face = face;
  scene.faces[face].patches.push_back(static_cast<int>(scene.patches.size()));
  scene.faces[face].area += p.area;
  scene.patches.push_back(std::move(p));
}

}  // namespace

void FaceTallies::Tally::add(std::size_t line, double value) {
  if (count++ == 0) first_line = line;
  worst = std::max(worst, value);
}

int default_material(Scene& scene, std::size_t line, FaceTallies& tallies) {
  tallies.no_material.add(line, 0.0);
  for (std::size_t m = 0; m < scene.materials.size(); ++m)
    if (scene.materials[m].name == kDefaultMaterialName) return static_cast<int>(m);
  scene.materials.push_back(Material{kDefaultMaterialName, Rgb::Constant(kDefaultReflectance), Rgb::Zero()});
  return static_cast<int>(scene.materials.size()) - 1;
}

void add_input_face(Scene& scene, InputFace face, std::vector<Vec3> v, double step, const ObjReadOptions& options,
                    FaceTallies& tallies) {
  const std::size_t line = face.line;
  const int fi = static_cast<int>(scene.faces.size());
  scene.faces.push_back(std::move(face));
  v.erase(std::unique(v.begin(), v.end()), v.end());
  while (v.size() > 1 && v.front() == v.back()) v.pop_back();
  const double diameter = v.size() >= 3 ? polygon_diameter(v) : 0.0;
  const Vec3 n = v.size() >= 3 ? newell_normal(v) : Vec3::Zero();
  // Zero area: relative to the diameter so that the test does not depend on the unit of length.
  if (v.size() < 3 || !(0.5 * n.norm() > 1e-14 * diameter * diameter)) {
    tallies.zero_area.add(line, 0.0);
    return;
  }
  const Vec3 unit = n.normalized();
  // Planar within what the file could print: a coordinate rounded to a step q moves its vertex by at
  // most (sqrt(3) / 2) q off the true plane, and the fitted plane moves as much, so sqrt(3) q; and
  // never tighter than planarity_tolerance of the diameter (see ObjReadOptions).
  const double deviation = planarity_deviation(v, unit);
  const bool planar = deviation <= std::max(options.planarity_tolerance * diameter, std::sqrt(3.0) * step);
  if (!planar) tallies.non_planar.add(line, deviation / diameter);
  if (planar && v.size() <= 4 && is_convex(v, unit)) {
    add_patch(scene, fi, v);
    return;
  }
  for (const auto& tri : triangulate(v, unit)) {
    std::vector<Vec3> t = {v[tri[0]], v[tri[1]], v[tri[2]]};
    if (0.5 * newell_normal(t).norm() > 1e-14 * diameter * diameter) add_patch(scene, fi, std::move(t));
  }
}

void report_tallies(const std::string& path, const FaceTallies& t, std::vector<std::string>* warnings) {
  if (warnings == nullptr) return;
  const auto warn = [&](std::size_t line, const std::string& message) {
    warnings->push_back(fmt::format("{}:{}: warning: {}", path, line, message));
  };
  if (t.no_material.count > 0)
    warn(t.no_material.first_line,
         fmt::format("{} no material (no usemtl before it, or a name no MTL defines): the default material "
                     "'{}' (reflectance {}, no emission) is used",
                     t.no_material.count == 1 ? "this face has"
                                              : fmt::format("this face and {} more have", t.no_material.count - 1),
                     kDefaultMaterialName, kDefaultReflectance));
  if (t.zero_area.count == 1) warn(t.zero_area.first_line, "zero-area face skipped");
  if (t.zero_area.count > 1)
    warn(t.zero_area.first_line, fmt::format("{} zero-area faces skipped (the first here)", t.zero_area.count));
  if (t.non_planar.count == 1)
    warn(t.non_planar.first_line,
         fmt::format("face is non-planar by {:.3g} of its diameter: split into triangles", t.non_planar.worst));
  if (t.non_planar.count > 1)
    warn(t.non_planar.first_line, fmt::format("{} faces are non-planar by up to {:.3g} of their diameter (the first "
                                              "here): split into triangles",
                                              t.non_planar.count, t.non_planar.worst));
}

}  // namespace hrad::detail
