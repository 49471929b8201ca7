#include "hrad/geometry/front_patch.h"

#include <algorithm>
#include <cmath>

#include "hrad/geometry/patch_plane.h"

namespace hrad {
namespace {

double scene_size(const Scene& scene) {
  if (scene.patches.empty()) return 0.0;
  const auto [lo, hi] = scene.bounds();
  return std::max({(hi - lo).norm(), lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()});
}

}  // namespace

double probe_tolerance(const Scene& scene) { return 1e-6 * scene_size(scene); }

bool on_patch(const Patch& p, const Vec3& x, double tolerance) {
  if (std::abs(p.normal.dot(x) - detail::plane_offset(p)) > tolerance) return false;
  for (std::size_t k = 0; k < p.vertices.size(); ++k) {
    const Vec3& a = p.vertices[k];
    const Vec3 edge = p.vertices[(k + 1) % p.vertices.size()] - a;
    // Counter-clockwise about the normal: inside is to the left of every edge.
    if (edge.cross(x - a).dot(p.normal) < -tolerance * edge.norm()) return false;
  }
  return true;
}

int front_patch_at(const Scene& scene, const Vec3& x, const Vec3& normal, double tolerance) {
  for (std::size_t pi = 0; pi < scene.patches.size(); ++pi) {
    const Patch& p = scene.patches[pi];
    if (normal.dot(p.normal) >= 1.0 - 1e-6 && on_patch(p, x, tolerance)) return static_cast<int>(pi);
  }
  return -1;
}

}  // namespace hrad
