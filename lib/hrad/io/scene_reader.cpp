#include "hrad/io/scene_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <tuple>

#include <fmt/format.h>

#include "hrad/core/memory.h"

#include "hrad/core/error.h"
#include "hrad/io/emitter_planes.h"
#include "hrad/io/flush_faces.h"
#include "hrad/io/near_faces.h"
#include "hrad/io/input_file.h"
#include "hrad/io/ply_file.h"
#include "hrad/io/scene_directives.h"
#include "hrad/io/scene_faces.h"

namespace hrad {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

/// The scene material with this reflectance and emission (one per distinct pair), checked.
int material_for(Scene& scene, const std::string& path, const std::string& where, const Rgb& rho, const Rgb& e,
                 const std::string& name_hint) {
  if (!rho.allFinite() || (rho < 0.0).any() || (rho >= 1.0).any())
    throw Error(fmt::format("{}: {}: reflectance {} {} {} is outside [0, 1)", path, where, rho[0], rho[1], rho[2]));
  if (!e.allFinite() || (e < 0.0).any())
    throw Error(fmt::format("{}: {}: emission {} {} {} is negative or not finite", path, where, e[0], e[1], e[2]));
  for (std::size_t m = 0; m < scene.materials.size(); ++m)
    if ((scene.materials[m].reflectance == rho).all() && (scene.materials[m].emission == e).all() &&
        scene.materials[m].name != kDefaultMaterialName)
      return static_cast<int>(m);
  scene.materials.push_back(
      Material{name_hint.empty() ? fmt::format("material_{}", scene.materials.size()) : name_hint, rho, e});
  return static_cast<int>(scene.materials.size()) - 1;
}

}  // namespace

Scene read_ply_scene(const std::string& path, std::vector<std::string>* warnings, const ObjReadOptions& options) {
  const std::string bytes = read_input_file(path);
  if (!looks_like_ply(bytes)) throw Error(fmt::format("{}: not a PLY file (it does not start with 'ply')", path));
  const PlyData ply = parse_ply(path, bytes);
  const PlyElement* vertex = ply.element("vertex");
  const PlyElement* face = ply.element("face");
  if (vertex == nullptr || face == nullptr)
    throw Error(fmt::format("{}: a PLY scene needs 'vertex' and 'face' elements", path));
  if (face->property("radiosity_r") && face->property("patch"))
    throw Error(
        fmt::format("{}: this is a solution written by 'hrad solve' (per-element radiosity), not a scene: solve "
                    "the scene it came from, or draw it with 'hrad render'",
                    path));
  const auto scalar = [&](const PlyElement& e, const char* name) -> const std::vector<double>* {
    const PlyProperty* p = e.property(name);
    return p != nullptr && !p->list ? &p->values : nullptr;
  };
  const auto* x = scalar(*vertex, "x");
  const auto* y = scalar(*vertex, "y");
  const auto* z = scalar(*vertex, "z");
  if (!x || !y || !z) throw Error(fmt::format("{}: element 'vertex' has no x, y and z", path));
  const PlyProperty* indices = face->property("vertex_indices");
  if (indices == nullptr) indices = face->property("vertex_index");
  if (indices == nullptr || !indices->list)
    throw Error(fmt::format("{}: element 'face' has no list property 'vertex_indices'", path));
  // Colour triples: (property names, scale) for reflectance and emission, on faces or vertices.
  const auto triple = [&](const PlyElement& e, const char* r, const char* g, const char* b) {
    std::array<const std::vector<double>*, 3> t = {scalar(e, r), scalar(e, g), scalar(e, b)};
    return t[0] && t[1] && t[2] ? std::optional(t) : std::nullopt;
  };
  const auto colour_scale = [&](const PlyElement& e) {
    const PlyProperty* p = e.property("red");
    return p != nullptr && (p->type == "uchar" || p->type == "uint8") ? 1.0 / 255.0 : 1.0;
  };
  const auto face_rho = triple(*face, "reflectance_r", "reflectance_g", "reflectance_b");
  const auto face_rgb = triple(*face, "red", "green", "blue");
  const auto face_e = triple(*face, "emission_r", "emission_g", "emission_b");
  const auto vertex_rgb = triple(*vertex, "red", "green", "blue");
  const auto vertex_e = triple(*vertex, "emission_r", "emission_g", "emission_b");

  Scene scene;
  scene.path = path;
  scene.files.push_back(path);
  for (std::size_t c = 0; c < ply.comments.size(); ++c)
    detail::apply_scene_comment(scene, path, ply.comment_lines[c], ply.comments[c]);
  detail::FaceTallies tallies;
  for (std::size_t f = 0; f < face->count; ++f) {
    const std::string where = fmt::format("face {}", f);
    std::vector<Vec3> v;
    std::vector<std::size_t> ids;
    for (std::size_t k = indices->offsets[f]; k < indices->offsets[f + 1]; ++k) {
      const double i = indices->values[k];
      if (!(i >= 0 && i < static_cast<double>(vertex->count) && i == std::floor(i)))
        throw Error(fmt::format("{}: {}: vertex index {} out of range ({} vertices)", path, where, i, vertex->count));
      const auto vi = static_cast<std::size_t>(i);
      ids.push_back(vi);
      v.emplace_back((*x)[vi], (*y)[vi], (*z)[vi]);
      if (!v.back().allFinite() || v.back().cwiseAbs().maxCoeff() > options.max_abs_coordinate)
        throw Error(fmt::format("{}: vertex {}: coordinates not finite or out of range", path, vi));
    }
    const auto mean_of = [&](const std::array<const std::vector<double>*, 3>& t, double scale) {
      Rgb sum = Rgb::Zero();
      for (std::size_t vi : ids) sum += Rgb((*t[0])[vi], (*t[1])[vi], (*t[2])[vi]);
      return Rgb(scale * sum / static_cast<double>(std::max<std::size_t>(ids.size(), 1)));
    };
    const auto at_face = [&](const std::array<const std::vector<double>*, 3>& t, double scale) {
      return Rgb(scale * (*t[0])[f], scale * (*t[1])[f], scale * (*t[2])[f]);
    };
    InputFace input;
    input.line = f + 1;
    const Rgb e = face_e ? at_face(*face_e, 1.0) : vertex_e ? mean_of(*vertex_e, 1.0) : Rgb(Rgb::Zero());
    if (face_rho || face_rgb || vertex_rgb) {
      const Rgb rho = face_rho   ? at_face(*face_rho, 1.0)
                      : face_rgb ? at_face(*face_rgb, colour_scale(*face))
                                 : mean_of(*vertex_rgb, colour_scale(*vertex));
      input.material = material_for(scene, path, where, rho, e, "");
    } else if ((e > 0.0).any()) {
      input.material = material_for(scene, path, where, Rgb::Constant(kDefaultReflectance), e, "");
    } else {
      input.material = detail::default_material(scene, input.line, tallies);
    }
    detail::add_input_face(scene, std::move(input), std::move(v), 0.0, options, tallies);
  }
  detail::report_tallies(path, tallies, warnings);
  if (scene.patches.empty()) throw Error(fmt::format("{}: no patch left (no face with a positive area)", path));
  return scene;
}

Scene read_scene(const std::string& path, std::vector<std::string>* warnings, const ObjReadOptions& options) {
  const std::string ext = lower_extension(path);
  const AllocationScope allocating(fmt::format("the scene read from {}", path), "read a smaller scene");
  Scene scene = ext == ".ply"                     ? read_ply_scene(path, warnings, options)
                : ext == ".gltf" || ext == ".glb" ? read_gltf_scene(path, warnings, options)
                                                  : read_obj_scene(path, warnings, options);
  const double total = scene.total_area();
  const FlushCuts cuts = cut_flush_faces(scene);
  if (cuts.pairs > 0 && warnings != nullptr) {
    const std::size_t top = scene.faces[static_cast<std::size_t>(cuts.first_top)].line;
    const std::size_t beneath = scene.faces[static_cast<std::size_t>(cuts.first_beneath)].line;
    warnings->push_back(fmt::format(
        "{}:{}: warning: {} pair{} of faces lie flush on each other (one plane, facing the same way, overlapping; "
        "first: line {} on line {}): the face of the smaller object (then the smaller face, then the later one) is "
        "taken to lie on top, and what it covers is cut out of the face beneath ({:.3g}% of the area{}); lift a "
        "face off the plane (a tenth of a millimetre will do) to say otherwise",
        path, top, cuts.pairs, cuts.pairs == 1 ? "" : "s", top, beneath, 100.0 * cuts.covered_area / total,
        cuts.hidden_faces > 0
            ? fmt::format("; {} face{} covered entirely", cuts.hidden_faces, cuts.hidden_faces == 1 ? "" : "s")
            : std::string()));
  }
  if (options.cut_near_faces) cut_near_faces(scene);
  if (options.cut_emitter_planes) cut_emitter_planes(scene);
  return scene;
}

}  // namespace hrad
