#include "hrad/io/emitter_planes.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "hrad/geometry/convex_clip.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

struct Box {
  Vec3 lo, hi;
  explicit Box(const std::vector<Vec3>& vertices) : lo(Vec3::Constant(INFINITY)), hi(Vec3::Constant(-INFINITY)) {
    for (const Vec3& v : vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  }
  bool overlaps(const Box& o) const { return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all(); }
};

}  // namespace

EmitterPlaneCuts cut_emitter_planes(Scene& scene, double reach) {
  EmitterPlaneCuts cuts;
  if (scene.patches.empty() || !(reach > 0.0)) return cuts;
  const auto [lo, hi] = scene.bounds();
  const double size = (hi - lo).norm(), eps = 1e-9 * size;
  // Only emitters whose direct light stands out from the light the room already has: brighter than
  // the mean radiosity a closed room of the scene's mean emission and reflectance would have,
  // E_mean / (1 - rho_mean) (channels summed). In a furnace, where everything emits alike, none.
  double area = 0.0, power = 0.0, reflected = 0.0;
  for (const Patch& p : scene.patches) {
    const Material& m = scene.materials[static_cast<std::size_t>(p.material)];
    area += p.area, power += p.area * m.emission.sum(), reflected += p.area * m.reflectance.mean();
  }
  const double mean_radiosity = power / area / std::max(1.0 - reflected / area, 1e-3);
  std::vector<int> emitters;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Material& m = scene.materials[static_cast<std::size_t>(scene.patches[i].material)];
    if (m.is_emitter() && m.emission.sum() > mean_radiosity) emitters.push_back(static_cast<int>(i));
  }
  if (emitters.empty()) return cuts;
  // Candidate (patch, emitter) pairs whose boxes, the emitter's grown by its reach, overlap: a sweep
  // along x over both kinds of box.
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
    Box grown(scene.patches[static_cast<std::size_t>(e)].vertices);
    const double near = reach * polygon_diameter(scene.patches[static_cast<std::size_t>(e)].vertices);
    grown.lo.array() -= near, grown.hi.array() += near;
    items.push_back({grown, e, true});
  }
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
    return std::tuple{a.box.lo.x(), a.patch, a.emitter} < std::tuple{b.box.lo.x(), b.patch, b.emitter};
  });
  std::vector<std::vector<int>> planes(scene.patches.size());
  const auto crosses = [&](int patch, int e) {
    if (patch == e) return false;
    const Patch& pe = scene.patches[static_cast<std::size_t>(e)];
    double below = 0.0, above = 0.0;
    for (const Vec3& v : scene.patches[static_cast<std::size_t>(patch)].vertices) {
      const double s = pe.normal.dot(v - pe.vertices[0]);
      below = std::min(below, s), above = std::max(above, s);
    }
    return below < -eps && above > eps;
  };
  std::vector<const Item*> active[2];  // [0] patches, [1] emitters, by the sweep still open
  for (const Item& it : items) {
    for (auto& list : active) std::erase_if(list, [&](const Item* a) { return a->box.hi.x() < it.box.lo.x(); });
    for (const Item* other : active[it.emitter ? 0 : 1]) {
      if (!it.box.overlaps(other->box)) continue;
      const int patch = it.emitter ? other->patch : it.patch, e = it.emitter ? it.patch : other->patch;
      if (crosses(patch, e)) planes[static_cast<std::size_t>(patch)].push_back(e);
    }
    active[it.emitter ? 1 : 0].push_back(&it);
  }
  for (std::vector<int>& list : planes) std::sort(list.begin(), list.end());
  std::vector<Patch> out;
  out.reserve(scene.patches.size());
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    if (planes[i].empty()) {
      out.push_back(p);
      continue;
    }
    const PatchFrame frame(p);
    std::vector<Polygon2> pieces = {frame.counter_clockwise(p.vertices)};
    for (const int e : planes[i]) {
      const Patch& pe = scene.patches[static_cast<std::size_t>(e)];
      // The emitter's plane in p's frame: s(u) = c + g.u, zero on the line where they meet.
      const Point2 g(pe.normal.dot(frame.e1), pe.normal.dot(frame.e2));
      const double c = pe.normal.dot(frame.origin - pe.vertices[0]);
      if (!(g.squaredNorm() > 1e-18)) continue;
      const Point2 a = -c * g / g.squaredNorm(), b = a + Point2(-g.y(), g.x());
      std::vector<Polygon2> next;
      for (Polygon2& piece : pieces) {
        Polygon2 front = clip(piece, a, b, false), back = clip(piece, a, b, true);
        const double whole = std::abs(signed_area(piece));
        const double least = kEmitterPlaneSliver * whole;
        if (front.size() >= 3 && back.size() >= 3 && std::abs(signed_area(front)) >= least &&
            std::abs(signed_area(back)) >= least) {
          next.push_back(std::move(front)), next.push_back(std::move(back));
          ++cuts.pairs;
        } else {
          next.push_back(std::move(piece));
        }
      }
      pieces = std::move(next);
    }
    append_pieces(p, frame, pieces, size, &out);
  }
  if (cuts.pairs == 0) return cuts;
  const std::size_t before = scene.patches.size();
  scene.patches = std::move(out);
  cuts.patches_added = scene.patches.size() > before ? scene.patches.size() - before : 0;
  relink_faces(scene);
  return cuts;
}

}  // namespace hrad
