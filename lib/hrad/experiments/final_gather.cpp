#include "hrad/experiments/final_gather.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/geometry/polygon.h"
#include "hrad/visibility/sampling.h"
#include "hrad/visibility/visibility.h"

namespace hrad {
namespace {

// The visible fraction of `leaf` from x weighted by the point-to-area kernel cos(theta_x) cos(theta_y)
// / r^2 over stratified points of the leaf, so that F(x -> leaf) times it is the occluded factor
// to the sampling error (Wallace, Elmquist & Haines 1989 for the kernel-weighted estimate).
double weighted_fraction(const Visibility& visibility, const Vec3& x, const Vec3& nx, int patch_x,
                         std::span<const Vec3> leaf, int leaf_patch, int samples, std::uint64_t seed) {
  detail::Rng rng(detail::mix_seed(seed, 7));
  std::vector<Vec2> uv;
  detail::stratified_unit_square(samples, rng, &uv);
  const detail::PolygonSampler sampler(leaf);
  const Vec3 ny = newell_normal(leaf).normalized();
  double weight = 0.0, visible = 0.0;
  int seen = 0;
  for (const Vec2& u : uv) {
    const Vec3 y = sampler.point(u.x(), u.y());
    const Vec3 d = y - x;
    const double k = detail::point_pair_kernel(nx, ny, d);
    const bool open = !visibility.segment_blocked(x, patch_x, y, leaf_patch);
    weight += k;
    visible += open ? k : 0.0;
    seen += open ? 1 : 0;
  }
  if (!(weight > 0.0)) return uv.empty() ? 1.0 : double(seen) / static_cast<double>(uv.size());
  return visible / weight;
}

constexpr std::int8_t kUnclassified = -1;

}  // namespace

std::vector<Rgb> final_gather_reflected(const Scene& scene, const Solution& solution,
                                        std::span<const SurfaceSample> points, const FinalGatherOptions& options) {
  const std::unique_ptr<Visibility> visibility = make_visibility(scene);
  const bool occlusion = visibility->scene_has_occlusion();
  std::vector<std::vector<Vec3>> leaves(solution.faces.size());
  for (std::size_t f = 0; f < solution.faces.size(); ++f)
    for (int v : solution.faces[f]) leaves[f].push_back(solution.vertices[v]);

  std::vector<Rgb> out(points.size(), Rgb::Zero());
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  std::unique_ptr<tbb::global_control> limit;
  if (options.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, options.threads);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 8), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<std::int8_t> patch_class(scene.patches.size(), kUnclassified);
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const SurfaceSample& s = points[i];
      const Patch& patch = scene.patches[static_cast<std::size_t>(s.patch)];
      const Rgb rho = scene.material_of(patch).reflectance;
      Rgb gathered = Rgb::Zero();
      // Each source patch classified once from x: a patch fully visible or hidden from x makes all
      // its leaves so (the classification is conservative both ways), so only the leaves of
      // partly visible patches are classified and sampled one by one. The same sums in the same
      // order as classifying every leaf.
      std::fill(patch_class.begin(), patch_class.end(), kUnclassified);
      for (std::size_t f = 0; f < leaves.size(); ++f) {
        const int source_patch = solution.face_patch[f];
        if (source_patch == s.patch) continue;  // a planar patch does not see itself
        std::int8_t& whole = patch_class[static_cast<std::size_t>(source_patch)];
        if (occlusion && whole == kUnclassified) {
          const Patch& source = scene.patches[static_cast<std::size_t>(source_patch)];
          whole = static_cast<std::int8_t>(
              visibility->estimate_from_point(s.position, s.patch, source.vertices, source_patch, 0, 0).pair_class);
        }
        if (whole == static_cast<std::int8_t>(PairClass::kFacingAway) || whole == static_cast<std::int8_t>(PairClass::kFullyHidden))
          continue;
        const double factor = point_to_polygon(s.position, patch.normal, leaves[f]);
        if (factor <= 0.0) continue;
        double seen = 1.0;
        if (occlusion && whole == static_cast<std::int8_t>(PairClass::kPartial)) {
          // Seed by point and leaf: the same reference whatever the thread count. One sample
          // classifies (exact when fully visible or hidden); a partly visible leaf is sampled.
          const std::uint64_t seed = (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(f);
          const VisibilityEstimate c = visibility->estimate_from_point(s.position, s.patch, leaves[f], source_patch, 1, seed);
          if (c.pair_class == PairClass::kPartial)
            seen = weighted_fraction(*visibility, s.position, patch.normal, s.patch, leaves[f], source_patch,
                                     options.visibility_samples, seed);
          else
            seen = c.fraction;
        }
        gathered += factor * seen * solution.face_radiosity[f];
      }
      out[i] = rho * gathered;
      const std::size_t n = done.fetch_add(1, std::memory_order_relaxed) + 1;
      if (options.progress && n % 256 == 0) {
        const std::lock_guard<std::mutex> lock(progress_mutex);
        options.progress(n, points.size());
      }
    }
  });
  if (options.progress) options.progress(points.size(), points.size());
  return out;
}

}  // namespace hrad
