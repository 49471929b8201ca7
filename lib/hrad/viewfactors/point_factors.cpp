#include "hrad/viewfactors/point_factors.h"

#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/visibility/visibility.h"

namespace hrad {

double point_factor_to_region(const Vec3& x, const Vec3& n, const VisibleRegion& region) {
  double f = 0.0;
  for (const PolygonWithHoles3& piece : region.pieces) {
    f += point_to_polygon(x, n, piece.outer);
    for (const std::vector<Vec3>& hole : piece.holes) {
      // Holes are clockwise seen from the front: reversed, Lambert's formula gives their factor.
      const std::vector<Vec3> ccw(hole.rbegin(), hole.rend());
      f -= point_to_polygon(x, n, ccw);
    }
  }
  return f;
}

PointFactors point_view_factors(const Scene& scene, const SurfaceUnits& units, std::span<const ProbePoint> points,
                                int threads, const ProgressSink& progress) {
  PointFactors out;
  out.points = static_cast<int>(points.size());
  out.units = units.size();
  out.factor.assign(points.size() * static_cast<std::size_t>(out.units), 0.0);
  const std::unique_ptr<Visibility> visibility =
      make_visibility(scene, VisibilityOptions{.exact_shaft_contacts = true});
  Effects effects;
  effects.visibility = visibility->scene_has_occlusion();
  const FormFactorEvaluator evaluator(scene, effects, visibility.get(), 64, FormFactorKernel::kAnalytic);
  std::atomic<std::uint64_t> visible{0}, hidden{0}, partial{0};
  ProgressReporter report("point factors", points.size(), "points", progress);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, points.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const Vec3& x = points[i].position;
            const Vec3& n = points[i].normal;
            const std::vector<Vec3> apex = {x};
            for (std::size_t p = 0; p < scene.patches.size(); ++p) {
              const int u = units.of_patch(scene, static_cast<int>(p));
              if (u < 0) continue;
              const Patch& patch = scene.patches[p];
              const double full = point_to_polygon(x, n, patch.vertices);
              if (!(full > 0.0)) continue;
              double f = full;
              switch (evaluator.classify(apex, -1, patch.vertices, static_cast<int>(p), nullptr, nullptr)) {
                case PairClass::kFullyHidden:
                case PairClass::kFacingAway:
                  f = 0.0;
                  ++hidden;
                  break;
                case PairClass::kFullyVisible:
                  ++visible;
                  break;
                case PairClass::kPartial:
                  f = std::min(full, point_factor_to_region(
                                         x, n, visible_region(scene, x, -1, patch.vertices, static_cast<int>(p))));
                  f = std::max(0.0, f);
                  ++partial;
                  break;
              }
              out.factor[i * static_cast<std::size_t>(out.units) + static_cast<std::size_t>(u)] += f;
            }
            report.advance();
          }
        });
  });
  report.finish();
  out.visible = visible;
  out.hidden = hidden;
  out.partial = partial;
  return out;
}

}  // namespace hrad
