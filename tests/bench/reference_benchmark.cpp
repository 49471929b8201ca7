// The Monte Carlo reference's throughput on the bundled Cornell box: rays per second of its ray
// caster (closest hits from surface points in cosine-distributed directions, the bounces of a
// path; segments between surface points and the light, its shadow rays), and paths per second of
// the whole estimator (rays/s counted from the summary: every ray the paths cast).
//
//   build/bin/reference_benchmark --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "hrad/core/rng.h"
#include "hrad/geometry/polygon.h"
#include "hrad/io/obj_reader.h"
#include "hrad/reference/area_sampler.h"
#include "hrad/reference/embree_scene.h"
#include "hrad/reference/reference.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

const Scene& cornell() {
  static const Scene scene = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  return scene;
}

struct Ray {
  Vec3 origin, direction, target;
};

// 4096 surface points (uniform by area), each with a cosine-distributed direction and a point on the light.
std::vector<Ray> surface_rays(const Scene& scene) {
  std::vector<int> all(scene.patches.size());
  std::vector<double> unit(scene.patches.size(), 1.0), light(scene.patches.size(), 0.0);
  for (std::size_t p = 0; p < all.size(); ++p) {
    all[p] = static_cast<int>(p);
    light[p] = scene.material_of(scene.patches[p]).emission.sum();
  }
  const detail::AreaSampler surfaces(scene, all, unit), lights(scene, all, light);
  detail::Rng rng(1);
  std::vector<Ray> rays;
  for (int i = 0; i < 4096; ++i) {
    const detail::SurfacePoint x = surfaces.sample(rng.uniform(), rng.uniform());
    const Vec3& n = scene.patches[static_cast<std::size_t>(x.patch)].normal;
    const auto [s, t] = plane_basis(n);
    const double u = rng.uniform(), phi = 2 * std::numbers::pi * rng.uniform();
    const Vec3 w = std::sqrt(u) * (std::cos(phi) * s + std::sin(phi) * t) + std::sqrt(1 - u) * n;
    rays.push_back({x.point, w, lights.sample(rng.uniform(), rng.uniform()).point});
  }
  return rays;
}

void BM_ClosestHitCornell(benchmark::State& state) {
  const EmbreeScene caster(cornell());
  const std::vector<Ray> rays = surface_rays(cornell());
  RayCounts counts;
  std::size_t i = 0, hits = 0;
  for (auto _ : state) {
    const Ray& r = rays[i++ % rays.size()];
    hits += caster.closest_hit(r.origin, r.direction, counts).patch >= 0 ? 1 : 0;
  }
  benchmark::DoNotOptimize(hits);
  state.counters["rays/s"] = benchmark::Counter(static_cast<double>(counts.total()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ClosestHitCornell);

void BM_ShadowRayCornell(benchmark::State& state) {
  const EmbreeScene caster(cornell());
  const std::vector<Ray> rays = surface_rays(cornell());
  RayCounts counts;
  std::size_t i = 0, blocked = 0;
  for (auto _ : state) {
    const Ray& r = rays[i++ % rays.size()];
    blocked += caster.blocked(r.origin, r.target, counts) ? 1 : 0;
  }
  benchmark::DoNotOptimize(blocked);
  state.counters["rays/s"] = benchmark::Counter(static_cast<double>(counts.total()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ShadowRayCornell);

// Paths per second of reference_faces on the Cornell box, 1024 points per face (35,840 paths, so
// that building the BVH, a few ms, is a small share), at 1 and 2 threads (real time: the work runs
// on TBB's threads).
void BM_PathsCornell(benchmark::State& state) {
  ReferenceOptions o;
  o.samples = 1024;
  o.threads = static_cast<int>(state.range(0));
  std::uint64_t paths = 0, rays = 0;
  for (auto _ : state) {
    std::vector<FaceEstimate> out;
    const ReferenceSummary s = reference_faces(cornell(), o, &out);
    paths += s.paths;
    rays += s.rays();
    ++o.seed;
  }
  state.counters["paths/s"] = benchmark::Counter(static_cast<double>(paths), benchmark::Counter::kIsRate);
  state.counters["rays/s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["rays/path"] = static_cast<double>(rays) / static_cast<double>(paths);
}
BENCHMARK(BM_PathsCornell)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hrad

BENCHMARK_MAIN();
