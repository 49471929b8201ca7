#include "hrad/core/scene.h"

#include <cmath>

namespace hrad {

double Scene::total_area() const {
  double sum = 0.0;
  for (const Patch& p : patches) sum += p.area;
  return sum;
}

std::pair<Vec3, Vec3> Scene::bounds() const {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Patch& p : patches)
    for (const Vec3& v : p.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  return {lo, hi};
}

int Scene::emitter_count() const {
  int n = 0;
  for (const InputFace& f : faces) n += materials[f.material].is_emitter() ? 1 : 0;
  return n;
}

void relink_faces(Scene& scene) {
  for (InputFace& f : scene.faces) {
    f.patches.clear();
    f.area = 0.0;
  }
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    InputFace& f = scene.faces[static_cast<std::size_t>(scene.patches[i].face)];
    f.patches.push_back(static_cast<int>(i));
    f.area += scene.patches[i].area;
  }
}

}  // namespace hrad
