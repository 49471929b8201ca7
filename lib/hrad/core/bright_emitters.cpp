#include "hrad/core/bright_emitters.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace hrad {
namespace {

struct Box {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  explicit Box(const std::vector<Vec3>& vertices) {
    for (const Vec3& v : vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  }
  bool overlaps(const Box& o) const { return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all(); }
};

}  // namespace

Rgb mean_radiosity(const Scene& scene) {
  Rgb emitted = Rgb::Zero(), reflectance = Rgb::Zero();
  double area = 0.0;
  for (const Patch& p : scene.patches) {
    const Material& m = scene.material_of(p);
    emitted += p.area * m.emission.abs();  // a fixed net flux (radiant exchange) may be negative
    reflectance += p.area * m.reflectance;
    area += p.area;
  }
  if (area <= 0.0) return Rgb::Zero();
  // Rhobar capped: a lossless scene with light in it has no finite mean, and the weights only need
  // to rank sources.
  const Rgb rho_bar = (reflectance / area).min(0.999);
  return (emitted / area) / (1.0 - rho_bar);
}

std::vector<int> bright_emitters(const Scene& scene) {
  const double mean = mean_radiosity(scene).sum();
  std::vector<int> out;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Material& m = scene.material_of(scene.patches[i]);
    if (m.is_emitter() && m.emission.sum() > mean) out.push_back(static_cast<int>(i));
  }
  return out;
}

std::vector<std::vector<int>> near_bright_emitters(const Scene& scene, double reach) {
  std::vector<std::vector<int>> near(scene.patches.size());
  const std::vector<int> emitters = bright_emitters(scene);
  if (emitters.empty()) return near;
  struct Item {
    Box box;
    int patch;
    bool emitter;
  };
  std::vector<Item> items;
  items.reserve(scene.patches.size() + emitters.size());
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    items.push_back({Box(scene.patches[i].vertices), static_cast<int>(i), false});
  for (const int e : emitters) {
    const Patch& pe = scene.patches[static_cast<std::size_t>(e)];
    Box grown(pe.vertices);
    double diameter = 0.0;
    for (const Vec3& u : pe.vertices)
      for (const Vec3& v : pe.vertices) diameter = std::max(diameter, (u - v).norm());
    grown.lo.array() -= reach * diameter, grown.hi.array() += reach * diameter;
    items.push_back({grown, e, true});
  }
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
    return std::tuple{a.box.lo.x(), a.patch, a.emitter} < std::tuple{b.box.lo.x(), b.patch, b.emitter};
  });
  std::vector<const Item*> active[2];  // [0] patches, [1] emitters, by the sweep still open
  for (const Item& it : items) {
    for (auto& list : active) std::erase_if(list, [&](const Item* a) { return a->box.hi.x() < it.box.lo.x(); });
    for (const Item* other : active[it.emitter ? 0 : 1]) {
      if (!it.box.overlaps(other->box)) continue;
      const int patch = it.emitter ? other->patch : it.patch, e = it.emitter ? it.patch : other->patch;
      if (patch != e) near[static_cast<std::size_t>(patch)].push_back(e);
    }
    active[it.emitter ? 1 : 0].push_back(&it);
  }
  for (std::vector<int>& list : near) std::sort(list.begin(), list.end());
  return near;
}

}  // namespace hrad
