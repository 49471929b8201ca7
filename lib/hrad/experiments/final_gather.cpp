#include "hrad/experiments/final_gather.h"

#include <memory>

#include <tbb/global_control.h>

#include "hrad/gather/leaf_gather.h"
#include "hrad/gather/link_gather.h"

namespace hrad {

std::vector<Rgb> final_gather_reflected(const Scene& scene, const Solution& solution,
                                        std::span<const SurfaceSample> points, const FinalGatherOptions& options,
                                        GatherWork* work) {
  std::unique_ptr<tbb::global_control> limit;
  if (options.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, options.threads);
  LeafGatherOptions o;
  o.tolerance = options.tolerance;
  o.partial = PartialSampling::per_node;
  o.visibility_samples = options.visibility_samples;
  o.classify_points = true;
  std::unique_ptr<FinalGather> gather;
  if (options.links != nullptr && options.links->hierarchy != nullptr) {
    LinkGatherOptions l;
    l.tolerance = options.tolerance;
    l.visibility_samples = options.link_rays;
    gather = std::make_unique<LinkGather>(scene, *options.links, l);
  } else {
    gather = std::make_unique<LeafGather>(scene, solution, o);
  }
  std::vector<GatherPoint> at(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    at[i] = {points[i].position, scene.patches[static_cast<std::size_t>(points[i].patch)].normal, points[i].patch};
  // The caller's (done, all) callback, at the reporter's pace (a call every 2 s at most).
  const ProgressReporter* reporter = nullptr;
  ProgressSink sink;
  if (options.progress) sink = [&](std::string_view) { options.progress(reporter->done(), points.size()); };
  ProgressReporter progress("final gather", points.size(), "points", sink);
  reporter = &progress;
  std::vector<Rgb> h = gather->gather(at, &progress);
  for (std::size_t i = 0; i < points.size(); ++i)
    h[i] *= scene.material_of(scene.patches[static_cast<std::size_t>(points[i].patch)]).reflectance;
  if (options.progress) options.progress(points.size(), points.size());
  if (work) *work = gather->work();
  return h;
}

}  // namespace hrad
