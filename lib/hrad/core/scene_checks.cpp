#include "hrad/core/scene_checks.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <tuple>

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

bool patches_overlap(const Patch& a, const Patch& b, const Vec3& n, double tol) {
  for (const Patch* edges : {&a, &b}) {
    const std::vector<Vec3>& v = edges->vertices;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Vec3 axis = (v[(i + 1) % v.size()] - v[i]).cross(n);
      const double len = axis.norm();
      if (len == 0.0) continue;
      double a_lo = INFINITY, a_hi = -INFINITY, b_lo = INFINITY, b_hi = -INFINITY;
      for (const Vec3& x : a.vertices) {
        a_lo = std::min(a_lo, x.dot(axis) / len);
        a_hi = std::max(a_hi, x.dot(axis) / len);
      }
      for (const Vec3& x : b.vertices) {
        b_lo = std::min(b_lo, x.dot(axis) / len);
        b_hi = std::max(b_hi, x.dot(axis) / len);
      }
      if (std::min(a_hi, b_hi) - std::max(a_lo, b_lo) <= tol) return false;
    }
  }
  return true;
}

std::vector<std::pair<int, int>> flush_pairs(const Scene& scene) {
  std::vector<std::pair<int, int>> pairs;
  if (scene.patches.empty()) return pairs;
  const auto [lo, hi] = scene.bounds();
  const double size = (hi - lo).norm(), tol = 1e-7 * size;
  // Bucketed by the plane, rounded; within a bucket, swept along the axis the normal leaves most
  // room in, so that a floor of many tiles costs O(tiles log tiles) when nothing overlaps.
  std::map<std::tuple<long long, long long, long long, long long>, std::vector<int>> planes;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    const auto q = [](double x, double step) { return static_cast<long long>(std::llround(x / step)); };
    planes[{q(p.normal.x(), 1e-6), q(p.normal.y(), 1e-6), q(p.normal.z(), 1e-6),
            q(p.normal.dot(p.vertices[0]), 1e-7 * size)}]
        .push_back(static_cast<int>(i));
  }
  for (const auto& [key, members] : planes) {
    if (members.size() < 2) continue;
    int axis = 0;
    scene.patches[static_cast<std::size_t>(members[0])].normal.cwiseAbs().minCoeff(&axis);
    struct Span {
      double lo, hi;
      int patch;
    };
    std::vector<Span> spans;
    for (const int i : members) {
      Span s{INFINITY, -INFINITY, i};
      for (const Vec3& v : scene.patches[static_cast<std::size_t>(i)].vertices)
        s.lo = std::min(s.lo, v[axis]), s.hi = std::max(s.hi, v[axis]);
      spans.push_back(s);
    }
    std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) {
      return std::pair{a.lo, a.patch} < std::pair{b.lo, b.patch};
    });
    for (std::size_t i = 0; i < spans.size(); ++i)
      for (std::size_t j = i + 1; j < spans.size() && spans[j].lo < spans[i].hi - tol; ++j) {
        const Patch& a = scene.patches[static_cast<std::size_t>(spans[i].patch)];
        const Patch& b = scene.patches[static_cast<std::size_t>(spans[j].patch)];
        if (a.face == b.face || !patches_overlap(a, b, a.normal, tol)) continue;
        pairs.emplace_back(std::min(spans[i].patch, spans[j].patch), std::max(spans[i].patch, spans[j].patch));
      }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<char> patches_facing_nothing(const Scene& scene) {
  std::vector<char> out(scene.patches.size(), 0);
  if (scene.patches.empty()) return out;
  const auto [lo, hi] = scene.bounds();
  const double tol = 1e-9 * (hi - lo).norm();
  // The vertices extreme along 26 directions settle most patches at once (one of them in front); a
  // patch with every corner of the scene's box on or behind its plane (by half the tolerance) has
  // nothing in front; only the rest scan every patch. The scan alone is quadratic where a floor is
  // tessellated: 3.6 s of `hrad info` on the 64,064-polygon pillar hall.
  std::vector<Vec3> extremes;
  for (int d = 0; d < 27; ++d) {
    const Vec3 dir(d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1);
    if (dir.isZero()) continue;
    const Vec3* best = nullptr;
    for (const Patch& q : scene.patches)
      for (const Vec3& v : q.vertices)
        if (best == nullptr || v.dot(dir) > best->dot(dir)) best = &v;
    extremes.push_back(*best);
  }
  std::array<Vec3, 8> corners;
  for (int k = 0; k < 8; ++k)
    corners[static_cast<std::size_t>(k)] =
        Vec3((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
  const auto sees_something = [&](const Patch& p) {
    const Vec3& o = p.vertices[0];
    for (const Vec3& v : extremes)
      if ((v - o).dot(p.normal) > tol) return true;
    double farthest = -INFINITY;  // the box's corner farthest in front of the plane
    for (const Vec3& corner : corners) farthest = std::max(farthest, (corner - o).dot(p.normal));
    if (farthest <= 0.5 * tol) return false;
    for (const Patch& q : scene.patches)
      if (&q != &p && in_front(p, q, tol)) return true;
    return false;
  };
  for (std::size_t i = 0; i < scene.patches.size(); ++i) out[i] = sees_something(scene.patches[i]) ? 0 : 1;
  return out;
}

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
  const std::vector<char> facing_nothing = patches_facing_nothing(scene);
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    if (facing_nothing[i]) {
      ++blind;
      blind_area += scene.patches[i].area;
    }
  if (scene.patches.size() > 1 && blind_area > 0.5 * scene.total_area())
    out.push_back(fmt::format(
        "{} of {} patches ({:.0f}% of the area) have no other face in front of them: their normals probably point "
        "out of the room; flip them (counter-clockwise vertex order seen from inside; Blender: Mesh > Normals > "
        "Flip or Recalculate Inside)",
        blind, scene.patches.size(), 100.0 * blind_area / scene.total_area()));

  // Faces of different input faces lying in one plane, facing the same way and overlapping (a
  // picture or a rug modelled flush with its wall or floor): light reaching the overlap lands on
  // both, so the scene absorbs more than it emits. The readers cut such overlaps (flush_faces.h);
  // a scene built otherwise may still have them.
  {
    std::size_t pairs = 0;
    double area = 0.0;
    std::string first;
    for (const auto& [i, j] : flush_pairs(scene)) {
      const Patch& a = scene.patches[static_cast<std::size_t>(i)];
      const Patch& b = scene.patches[static_cast<std::size_t>(j)];
      if (pairs++ == 0)
        first = fmt::format("faces at lines {} and {}", scene.faces[static_cast<std::size_t>(a.face)].line,
                            scene.faces[static_cast<std::size_t>(b.face)].line);
      area += std::min(a.area, b.area);
    }
    if (pairs > 0)
      out.push_back(fmt::format(
          "{} pair{} of patches lie in one plane, facing the same way, and overlap (first: {}; up to {:.3g}% of the "
          "area): light reaching an overlap lands on both, so the scene absorbs more than it emits; lift the face "
          "on top off its plane or cut it out of the one beneath (hrad::cut_flush_faces())",
          pairs, pairs == 1 ? "" : "s", first, 100.0 * area / scene.total_area()));
  }

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
