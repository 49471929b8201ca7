#include "hrad/io/scene_json.h"

namespace hrad {
namespace {

nlohmann::json rgb_json(const Rgb& c) { return {c[0], c[1], c[2]}; }
nlohmann::json vec_json(const Vec3& v) { return {v[0], v[1], v[2]}; }

}  // namespace

nlohmann::json scene_summary_json(const Scene& scene) {
  nlohmann::json j;
  j["file"] = scene.path;
  j["patches"] = scene.patches.size();
  j["input_faces"] = scene.faces.size();
  j["area"] = scene.total_area();
  nlohmann::json faces = nlohmann::json::array(), emitters = nlohmann::json::array();
  for (std::size_t i = 0; i < scene.faces.size(); ++i) {
    const InputFace& f = scene.faces[i];
    const Material& m = scene.materials[f.material];
    nlohmann::json e = {{"face", i},          {"line", f.line}, {"group", f.group},
                        {"material", m.name}, {"area", f.area}, {"patches", f.patches.size()}};
    if (m.is_emitter()) emitters.push_back(e);
    faces.push_back(std::move(e));
  }
  j["faces"] = std::move(faces);
  j["emitters"] = std::move(emitters);
  nlohmann::json materials = nlohmann::json::object();
  for (const Material& m : scene.materials)
    materials[m.name] = {{"reflectance", rgb_json(m.reflectance)}, {"emission", rgb_json(m.emission)}};
  j["materials"] = std::move(materials);
  if (scene.emission_units)
    j["emission_units"] = {{"unit", to_string(scene.emission_units->units)}, {"declared_at", scene.emission_units->where}};
  const auto [lo, hi] = scene.bounds();
  j["bounds"] = {{"min", vec_json(lo)}, {"max", vec_json(hi)}};
  return j;
}

}  // namespace hrad
