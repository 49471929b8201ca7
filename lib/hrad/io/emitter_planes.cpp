#include "hrad/io/emitter_planes.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "hrad/core/bright_emitters.h"
#include "hrad/geometry/convex_clip.h"
#include "hrad/geometry/polygon.h"

namespace hrad {

EmitterPlaneCuts cut_emitter_planes(Scene& scene, double reach) {
  EmitterPlaneCuts cuts;
  if (scene.patches.empty() || !(reach > 0.0)) return cuts;
  const auto [lo, hi] = scene.bounds();
  const double size = (hi - lo).norm(), eps = 1e-9 * size;
  // Only emitters whose direct light stands out from the light the room already has: in a furnace,
  // where everything emits alike, none (core/bright_emitters.h).
  const std::vector<std::vector<int>> near = near_bright_emitters(scene, reach);
  const auto crosses = [&](std::size_t patch, int e) {
    const Patch& pe = scene.patches[static_cast<std::size_t>(e)];
    double below = 0.0, above = 0.0;
    for (const Vec3& v : scene.patches[patch].vertices) {
      const double s = pe.normal.dot(v - pe.vertices[0]);
      below = std::min(below, s), above = std::max(above, s);
    }
    return below < -eps && above > eps;
  };
  std::vector<std::vector<int>> planes(scene.patches.size());
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    for (const int e : near[i])
      if (crosses(i, e)) planes[i].push_back(e);
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
