#include "hrad/core/scene.h"

namespace hrad {

double Scene::total_area() const {
  double sum = 0.0;
  for (const Patch& p : patches) sum += p.area;
  return sum;
}

int Scene::emitter_count() const {
  int n = 0;
  for (const InputFace& f : faces) n += materials[f.material].is_emitter() ? 1 : 0;
  return n;
}

}  // namespace hrad
