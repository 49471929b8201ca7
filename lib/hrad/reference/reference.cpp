#include "hrad/reference/reference.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <string_view>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "hrad/core/error.h"
#include "hrad/core/progress.h"
#include "hrad/core/rng.h"
#include "hrad/core/stopwatch.h"
#include "hrad/geometry/patch_plane.h"
#include "hrad/reference/area_sampler.h"
#include "hrad/reference/embree_scene.h"
#include "hrad/reference/path_tracer.h"
#include "hrad/reference/running_stats.h"

namespace hrad {
namespace {

// The seed of block `block` of query `query`: SplitMix64 outputs chained over the three numbers,
// so that neighbouring queries and blocks get unrelated streams.
std::uint64_t block_seed(std::uint64_t seed, std::uint64_t query, std::uint64_t block) {
  detail::Rng a(seed);
  detail::Rng b(a.next() ^ query);
  detail::Rng c(b.next() ^ block);
  return c.next();
}

// Runs `trace(query, block, rng, counts, stats)` for every block of every query in parallel and
// merges each query's blocks in block order.
template <class Trace>
std::vector<detail::RunningStats> run_blocks(std::size_t queries, const std::vector<int>& blocks_per_query,
                                             std::string_view unit, const ReferenceOptions& options, RayCounts* rays,
                                             const Trace& trace) {
  std::vector<std::size_t> first_item(queries + 1, 0);
  for (std::size_t q = 0; q < queries; ++q)
    first_item[q + 1] = first_item[q] + static_cast<std::size_t>(blocks_per_query[q]);
  const std::size_t items = first_item[queries];
  std::vector<std::size_t> item_query(items);
  for (std::size_t q = 0; q < queries; ++q)
    std::fill(item_query.begin() + static_cast<std::ptrdiff_t>(first_item[q]),
              item_query.begin() + static_cast<std::ptrdiff_t>(first_item[q + 1]), q);

  std::vector<detail::RunningStats> block_stats(items);
  std::vector<std::atomic<int>> blocks_left(queries);
  for (std::size_t q = 0; q < queries; ++q) blocks_left[q].store(blocks_per_query[q]);
  std::atomic<std::uint64_t> closest_hit{0}, shadow{0};
  ProgressReporter progress("reference", queries, std::string(unit), options.progress);
  // Queries with no block are done before any work.
  for (std::size_t q = 0; q < queries; ++q)
    if (blocks_per_query[q] == 0) progress.advance();

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, items, 1), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t item = r.begin(); item != r.end(); ++item) {
      const std::size_t q = item_query[item];
      const std::size_t block = item - first_item[q];
      detail::Rng rng(block_seed(options.seed, q, block));
      RayCounts counts;
      trace(q, block, rng, counts, block_stats[item]);
      closest_hit += counts.closest_hit;
      shadow += counts.shadow;
      if (blocks_left[q].fetch_sub(1) == 1) progress.advance();
    }
  });
  progress.finish();

  std::vector<detail::RunningStats> stats(queries);
  for (std::size_t q = 0; q < queries; ++q)
    for (std::size_t item = first_item[q]; item < first_item[q + 1]; ++item) stats[q].merge(block_stats[item]);
  rays->closest_hit += closest_hit.load();
  rays->shadow += shadow.load();
  return stats;
}

int block_count(std::uint64_t samples) { return static_cast<int>((samples + kPathsPerBlock - 1) / kPathsPerBlock); }

std::pair<int, int> block_range(std::size_t block, int samples) {
  const int begin = static_cast<int>(block) * kPathsPerBlock;
  return {begin, std::min(samples, begin + kPathsPerBlock)};
}

// What both queries share: the options checked, the thread limit, the ray caster and the path
// tracer, the timing and the ray counts. `run(tracer, counts)` traces and returns the paths.
template <class Run>
ReferenceSummary run_reference(const Scene& scene, const ReferenceOptions& options, const Run& run) {
  validate_reference_options(options);
  const Stopwatch total;
  std::unique_ptr<tbb::global_control> limit;
  if (options.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<std::size_t>(options.threads));
  ReferenceSummary summary;
  const EmbreeScene rays(scene);
  summary.build_seconds = total.seconds();
  const detail::PathTracer tracer(rays, options.max_depth, options.roulette_depth);
  const Stopwatch tracing;
  RayCounts counts;
  summary.paths = run(tracer, counts);
  summary.trace_seconds = tracing.seconds();
  summary.closest_hit_rays = counts.closest_hit;
  summary.shadow_rays = counts.shadow;
  summary.total_seconds = total.seconds();
  return summary;
}

}  // namespace

void validate_reference_options(const ReferenceOptions& o) {
  if (o.samples < 2) throw Error(fmt::format("--samples must be >= 2 (a standard error needs two), got {}", o.samples));
  if (o.max_depth < 0) throw Error(fmt::format("--max-depth must be >= 0 (0 = no limit), got {}", o.max_depth));
  if (o.roulette_depth < 1) throw Error(fmt::format("--roulette-depth must be >= 1, got {}", o.roulette_depth));
  if (o.threads < 0) throw Error(fmt::format("--threads must be >= 0 (0 = all cores), got {}", o.threads));
}

ReferenceSummary reference_points(const Scene& scene, std::span<const ProbePoint> points,
                                  const ReferenceOptions& options, std::vector<PointEstimate>* out) {
  return run_reference(scene, options, [&](const detail::PathTracer& tracer, RayCounts& counts) {
    // Points on a patch's front go onto its plane and face its normal.
    const double tolerance = probe_tolerance(scene);
    std::vector<PointEstimate> estimates(points.size());
    std::vector<Vec3> position(points.size()), normal(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      position[i] = points[i].position;
      normal[i] = points[i].normal.normalized();
      const int patch = front_patch_at(scene, position[i], normal[i], tolerance);
      estimates[i].patch = patch;
      if (patch >= 0) {
        const Patch& p = scene.patches[static_cast<std::size_t>(patch)];
        position[i] -= p.normal * (p.normal.dot(position[i]) - detail::plane_offset(p));
        normal[i] = p.normal;
      }
    }

    const std::vector<int> blocks(points.size(), block_count(static_cast<std::uint64_t>(options.samples)));
    const std::vector<detail::RunningStats> stats =
        run_blocks(points.size(), blocks, "points", options, &counts,
                   [&](std::size_t q, std::size_t block, detail::Rng& rng, RayCounts& c, detail::RunningStats& s) {
                     const auto [begin, end] = block_range(block, options.samples);
                     for (int k = begin; k < end; ++k) s.add(tracer.irradiance(position[q], normal[q], rng, c));
                   });

    std::uint64_t paths = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      PointEstimate& e = estimates[i];
      e.irradiance = stats[i].mean;
      e.irradiance_se = stats[i].standard_error();
      if (e.patch >= 0) {
        const Material& m = scene.material_of(scene.patches[static_cast<std::size_t>(e.patch)]);
        e.radiosity = m.emission + m.reflectance * e.irradiance;
        e.radiosity_se = m.reflectance * e.irradiance_se;
      }
      paths += stats[i].count;
    }
    if (out) *out = std::move(estimates);
    return paths;
  });
}

ReferenceSummary reference_faces(const Scene& scene, const ReferenceOptions& options, std::vector<FaceEstimate>* out) {
  return run_reference(scene, options, [&](const detail::PathTracer& tracer, RayCounts& counts) {
    const std::size_t faces = scene.faces.size();
    const int samples = options.samples;
    // Stratified points on each face: one uniform point in each cell of a columns x rows grid of
    // the unit square (mapped onto the face by AreaSampler), the points beyond the grid uniform.
    const int columns = std::max(1, static_cast<int>(std::floor(std::sqrt(static_cast<double>(samples)))));
    const int rows = samples / columns;
    std::vector<detail::AreaSampler> samplers(faces);
    const std::vector<double> unit_weight(scene.patches.size(), 1.0);
    std::vector<int> blocks(faces, 0);
    for (std::size_t f = 0; f < faces; ++f) {
      samplers[f] = detail::AreaSampler(scene, scene.faces[f].patches, unit_weight);
      bool reflects = false;
      for (int p : scene.faces[f].patches)
        reflects =
            reflects || scene.material_of(scene.patches[static_cast<std::size_t>(p)]).reflectance.maxCoeff() > 0.0;
      if (reflects && !samplers[f].empty()) blocks[f] = block_count(static_cast<std::uint64_t>(samples));
    }

    const std::vector<detail::RunningStats> stats =
        run_blocks(faces, blocks, "faces", options, &counts,
                   [&](std::size_t f, std::size_t block, detail::Rng& rng, RayCounts& c, detail::RunningStats& s) {
                     const auto [begin, end] = block_range(block, samples);
                     for (int k = begin; k < end; ++k) {
                       double u = rng.uniform(), v = rng.uniform();
                       if (k < columns * rows) {
                         u = (k % columns + u) / columns;
                         v = (k / columns + v) / rows;
                       }
                       const detail::SurfacePoint x = samplers[f].sample(u, v);
                       const Patch& p = scene.patches[static_cast<std::size_t>(x.patch)];
                       const Material& m = scene.material_of(p);
                       s.add(m.emission + m.reflectance * tracer.irradiance(x.point, p.normal, rng, c));
                     }
                   });

    std::uint64_t paths = 0;
    std::vector<FaceEstimate> estimates(faces);
    for (std::size_t f = 0; f < faces; ++f) {
      paths += stats[f].count;
      if (blocks[f] > 0) {
        estimates[f].radiosity = stats[f].mean;
        estimates[f].radiosity_se = stats[f].standard_error();
      } else {
        // Nothing reflects: the radiosity is the emission, the same on each of its patches.
        const InputFace& face = scene.faces[f];
        estimates[f].radiosity =
            face.material >= 0 ? scene.materials[static_cast<std::size_t>(face.material)].emission : Rgb::Zero();
      }
    }
    if (out) *out = std::move(estimates);
    return paths;
  });
}

}  // namespace hrad
