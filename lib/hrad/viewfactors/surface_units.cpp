#include "hrad/viewfactors/surface_units.h"

#include <cassert>
#include <map>

#include <fmt/format.h>

namespace hrad {
namespace {

double face_emissivity(const Scene& scene, const InputFace& f) {
  if (f.material < 0) return 1.0;
  return 1.0 - scene.materials[static_cast<std::size_t>(f.material)].reflectance.mean();
}

}  // namespace

SurfaceUnits units_from_map(const Scene& scene, std::vector<int> of_face, std::vector<std::string> names,
                            std::vector<double> emissivity) {
  assert(of_face.size() == scene.faces.size());
  SurfaceUnits u;
  u.of_face = std::move(of_face);
  u.names = std::move(names);
  const std::size_t n = u.names.size();
  u.area.assign(n, 0.0);
  std::vector<double> weighted(n, 0.0);
  for (const Patch& p : scene.patches) {
    const int unit = u.of_face[static_cast<std::size_t>(p.face)];
    if (unit < 0) continue;
    u.area[static_cast<std::size_t>(unit)] += p.area;
    weighted[static_cast<std::size_t>(unit)] +=
        p.area * face_emissivity(scene, scene.faces[static_cast<std::size_t>(p.face)]);
  }
  if (emissivity.size() == n) {
    u.emissivity = std::move(emissivity);
  } else {
    u.emissivity.resize(n);
    for (std::size_t i = 0; i < n; ++i) u.emissivity[i] = u.area[i] > 0.0 ? weighted[i] / u.area[i] : 1.0;
  }
  return u;
}

SurfaceUnits face_units(const Scene& scene) {
  std::vector<int> of_face(scene.faces.size());
  std::vector<std::string> names(scene.faces.size());
  for (std::size_t f = 0; f < scene.faces.size(); ++f) {
    of_face[f] = static_cast<int>(f);
    names[f] = scene.faces[f].group.empty() ? fmt::format("face{}", f) : fmt::format("{}#{}", scene.faces[f].group, f);
  }
  return units_from_map(scene, std::move(of_face), std::move(names));
}

SurfaceUnits group_units(const Scene& scene) {
  std::vector<int> of_face(scene.faces.size());
  std::vector<std::string> names;
  std::map<std::string, int> index;
  for (std::size_t f = 0; f < scene.faces.size(); ++f) {
    const auto [it, added] = index.emplace(scene.faces[f].group, static_cast<int>(names.size()));
    if (added) names.push_back(scene.faces[f].group);
    of_face[f] = it->second;
  }
  return units_from_map(scene, std::move(of_face), std::move(names));
}

}  // namespace hrad
