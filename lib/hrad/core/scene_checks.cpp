#include "hrad/core/scene_checks.h"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

namespace hrad {
namespace {

bool named_like_a_light(std::string name) {
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* hint : {"light", "lamp", "emission", "emissive", "emit", "glow"})
    if (name.find(hint) != std::string::npos) return true;
  return false;
}

/// True when some vertex of `q` lies strictly in front of `p`'s plane (by more than `tol`).
bool in_front(const Patch& p, const Patch& q, double tol) {
  for (const Vec3& v : q.vertices)
    if ((v - p.vertices[0]).dot(p.normal) > tol) return true;
  return false;
}

}  // namespace

std::vector<std::string> scene_warnings(const Scene& scene) {
  std::vector<std::string> out;
  if (scene.patches.empty()) return out;
  const auto [lo, hi] = scene.bounds();
  const double tol = 1e-9 * (hi - lo).norm();

  for (const Material& m : scene.materials)
    if (!m.is_emitter() && named_like_a_light(m.name))
      out.push_back(fmt::format(
          "material '{}' looks like a light but emits nothing (Ke 0 or no Ke): Blender's OBJ exporter writes "
          "Emission shaders and lamps that way; give it Ke r g b (emitted exitance) in the MTL",
          m.name));
  if (scene.emitter_count() == 0)
    out.push_back("no face emits light (no material has Ke > 0): every radiosity will be 0");

  // Faces with nothing in front of them.
  std::size_t blind = 0;
  double blind_area = 0.0;
  for (const Patch& p : scene.patches) {
    bool sees = false;
    for (const Patch& q : scene.patches)
      if (&q != &p && in_front(p, q, tol)) {
        sees = true;
        break;
      }
    if (!sees) {
      ++blind;
      blind_area += p.area;
    }
  }
  if (scene.patches.size() > 1 && blind_area > 0.5 * scene.total_area())
    out.push_back(fmt::format(
        "{} of {} patches ({:.0f}% of the area) have no other face in front of them: their normals probably point "
        "out of the room; flip them (counter-clockwise vertex order seen from inside; Blender: Mesh > Normals > "
        "Flip or Recalculate Inside)",
        blind, scene.patches.size(), 100.0 * blind_area / scene.total_area()));

  // Light reaching something: an emitter and a receiver each in front of the other.
  if (scene.emitter_count() > 0) {
    bool reaches = false;
    for (const Patch& e : scene.patches) {
      if (!scene.material_of(e).is_emitter()) continue;
      for (const Patch& r : scene.patches)
        if (&r != &e && in_front(e, r, tol) && in_front(r, e, tol)) {
          reaches = true;
          break;
        }
      if (reaches) break;
    }
    if (!reaches)
      out.push_back(
          "no light reaches any surface: every emitter faces away from every other face (flip the emitters' normals?)");
  }
  return out;
}

}  // namespace hrad
