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

}  // namespace hrad
