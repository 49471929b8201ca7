// Throughput of the final gather (gather/leaf_gather.h) on the bundled Cornell box, solved by
// hierarchical radiosity at its defaults (and at a finer aeps, where grouping leaves pays):
//   * BM_GatheredImage: a gathered image (hrad render --final-gather's settings: shared rays, no
//     per-point classification), points/s;
//   * BM_GatherPoints: points on every patch (the sweep's error samples), per mode: the image's,
//     the probes' (classified, each partly visible node sampled on its own) and leaf by leaf
//     (tolerance 0, the sweep's reference), with the work per point;
//   * BM_LinkGatherPoints: the same points gathered through the solve's links (gather/link_gather.h);
//   * BM_LinkGatherLeafFirst: the probes' mode through the links, classifying from each leaf first or
//     from each point where the leaf holds few points;
//   * BM_LeafFactors: all leaves' point factors at those points, the plain contour sum against a
//     relative accuracy of 1e-9 (what the gather gives up by using the plain sum).
// Run one core at a time and quote ratios from one run:
//   taskset -c 0 build/bin/final_gather_benchmark --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <string>

#include <tbb/global_control.h>

#include "hrad/analysis/error_metrics.h"
#include "hrad/core/tone_map.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/gather/gathered_image.h"
#include "hrad/gather/leaf_gather.h"
#include "hrad/gather/link_gather.h"
#include "hrad/io/obj_reader.h"
#include "hrad/render/render.h"
#include "hrad/solvers/solve.h"
#include "hrad/solvers/solved_hierarchy.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

const Scene& cornell() {
  static const Scene s = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  return s;
}

// Hierarchical radiosity at its defaults (fine = false) or at aeps = total / 20000 (~10k leaves),
// with its hierarchy and links (for the gather through them).
struct Solved {
  Solution solution;
  SolvedHierarchy kept;
};

const Solved& solved(bool fine) {
  static const Solved coarse = [] {
    Solved s;
    solve(cornell(), SolveOptions{}, &s.solution, &s.kept);
    return s;
  }();
  static const Solved finer = [] {
    SolveOptions o;
    o.aeps = cornell().total_area() / 20000;
    Solved s;
    solve(cornell(), o, &s.solution, &s.kept);
    return s;
  }();
  return fine ? finer : coarse;
}

const Solution& solution(bool fine) { return solved(fine).solution; }

std::vector<GatherPoint> surface_points(int per_patch) {
  std::vector<GatherPoint> points;
  for (const SurfaceSample& s : patch_samples(cornell(), per_patch))
    points.push_back({s.position, cornell().patches[static_cast<std::size_t>(s.patch)].normal, s.patch});
  return points;
}

LeafGatherOptions mode(int m) {
  LeafGatherOptions o;
  if (m == 0) {  // the image's
    o.partial = PartialSampling::shared;
    o.classify_points = false;
    o.visibility_samples = 32;
  } else if (m == 2) {  // leaf by leaf
    o.tolerance = 0.0;
  }
  return o;
}

void set_work(benchmark::State& state, const GatherWork& w, std::size_t leaves) {
  const double p = w.points ? static_cast<double>(w.points) : 1.0;
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(w.points), benchmark::Counter::kIsRate);
  state.counters["factors/point"] = static_cast<double>(w.node_visits) / p;
  state.counters["leaves/point"] = static_cast<double>(w.leaves_covered) / p;
  state.counters["rays/point"] = static_cast<double>(w.rays) / p;
  state.counters["shafts/point"] = static_cast<double>(w.classifications) / p;
  state.counters["leaves"] = static_cast<double>(leaves);
}

void BM_GatheredImage(benchmark::State& state) {
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const Solution& s = solution(state.range(0) != 0);
  const LeafGather gather(cornell(), s, mode(0));
  RenderOptions o;
  o.camera = default_camera(s, 96, 96);
  o.exposure = auto_exposure(s);
  o.samples_per_pixel = 4;
  for (auto _ : state) benchmark::DoNotOptimize(render_gathered(s, gather, o).points);
  set_work(state, gather.work(), s.faces.size());
}
BENCHMARK(BM_GatheredImage)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

// Args: mode, fine solve, points per patch (256: the sweep's error samples).
void BM_GatherPoints(benchmark::State& state) {
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const Solution& s = solution(state.range(1) != 0);
  const LeafGather gather(cornell(), s, mode(static_cast<int>(state.range(0))));
  const std::vector<GatherPoint> points = surface_points(static_cast<int>(state.range(2)));
  for (auto _ : state) benchmark::DoNotOptimize(gather.gather(points).data());
  set_work(state, gather.work(), s.faces.size());
}
BENCHMARK(BM_GatherPoints)
    ->ArgsProduct({{0, 1, 2}, {0, 1}, {16}})
    ->Args({1, 0, 256})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

// The gather through the links (gather/link_gather.h) at the same points as BM_GatherPoints
// (args: fine solve, points per patch, classify each point, rays per partly visible source or, with
// shared rays, per point, shared rays): its defaults (0, 512, 1) beside 64 points on each partly
// visible source after a shaft test from the point (1, 64, 0). Compare with BM_GatherPoints/1 (the
// all-patches gather in the same per-source mode) at the same points.
void BM_LinkGatherPoints(benchmark::State& state) {
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const Solved& s = solved(state.range(0) != 0);
  LinkGatherOptions o;
  o.classify_points = state.range(2) != 0;
  o.visibility_samples = static_cast<int>(state.range(3));
  o.partial = state.range(4) != 0 ? PartialSampling::shared : PartialSampling::per_node;
  const LinkGather gather(cornell(), s.kept, o);
  const std::vector<GatherPoint> points = surface_points(static_cast<int>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(gather.gather(points).data());
  set_work(state, gather.work(), s.solution.faces.size());
}
BENCHMARK(BM_LinkGatherPoints)
    ->ArgsProduct({{0, 1}, {16, 256}, {0}, {512}, {1}})
    ->ArgsProduct({{0}, {16, 256}, {1}, {64}, {0}})
    ->ArgsProduct({{0}, {256}, {0}, {128, 256}, {1}})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

// The probes' mode through the links (64 points on each partly visible source, each classified
// from the point): a leaf holding fewer than leaf_first_points of the points classifies from each
// point straight away instead of from its polygon first (args: points per patch, leaf_first_points;
// 1 always classifies from the leaf first). The values are the same (link_gather_test).
void BM_LinkGatherLeafFirst(benchmark::State& state) {
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const Solved& s = solved(false);
  LinkGatherOptions o;
  o.classify_points = true;
  o.visibility_samples = 64;
  o.partial = PartialSampling::per_node;
  o.leaf_first_points = static_cast<int>(state.range(1));
  const LinkGather gather(cornell(), s.kept, o);
  const std::vector<GatherPoint> points = surface_points(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(gather.gather(points).data());
  set_work(state, gather.work(), s.solution.faces.size());
}
BENCHMARK(BM_LinkGatherLeafFirst)->ArgsProduct({{16, 256}, {1, 4}})->Unit(benchmark::kSecond)->Iterations(1);

void BM_LeafFactors(benchmark::State& state) {
  const Solution& s = solution(false);
  const std::vector<GatherPoint> points = surface_points(4);
  std::vector<std::vector<Vec3>> leaves;
  for (const auto& face : s.faces) {
    leaves.emplace_back();
    for (int v : face) leaves.back().push_back(s.vertices[static_cast<std::size_t>(v)]);
  }
  const double tolerance = state.range(0) ? 1e-9 : kLambertSumOnly;
  std::size_t factors = 0;
  for (auto _ : state) {
    double sum = 0.0;
    for (const GatherPoint& p : points)
      for (std::size_t f = 0; f < leaves.size(); ++f) {
        if (s.face_patch[f] == p.patch) continue;
        sum += point_to_polygon(p.position, p.normal, leaves[f], tolerance);
        ++factors;
      }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["factors/s"] = benchmark::Counter(static_cast<double>(factors), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LeafFactors)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hrad

BENCHMARK_MAIN();
