// Full matrix vs substructuring on the bundled Cornell box at their defaults, the two form-factor
// kernels on the same element pairs, and sampled visibility of a pair closer than its size (source
// points by solid angle) against the same pair far apart (by area). Run: build/bin/solvers_benchmark
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>
#include <vector>

#include "hrad/io/obj_reader.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/effects.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/solvers/solve.h"
#include "hrad/visibility/visibility.h"
#include "support/source_tree.h"

namespace {

const hrad::Scene& cornell() {
  static const hrad::Scene s =
      hrad::read_obj_scene(hrad::test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  return s;
}

void BM_CornellDefaults(benchmark::State& state) {
  hrad::SolveOptions o;
  o.method = static_cast<hrad::Method>(state.range(0));
  hrad::SolveSummary sum;
  for (auto _ : state) {
    hrad::Solution sol;
    sum = hrad::solve(cornell(), o, &sol);
    benchmark::DoNotOptimize(sol.patch_radiosity.data());
  }
  state.counters["elements"] = static_cast<double>(sum.elements);
  state.counters["links"] = static_cast<double>(sum.links);
  state.counters["ff_evals"] = static_cast<double>(sum.form_factor_evaluations);
  state.counters["vis_queries"] = static_cast<double>(sum.visibility_queries);
}
BENCHMARK(BM_CornellDefaults)
    ->Arg(static_cast<int>(hrad::Method::kFull))
    ->Arg(static_cast<int>(hrad::Method::kSubstructure))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// All pairs of 200 Cornell-box elements, unoccluded, per kernel.
void BM_KernelPairs(benchmark::State& state) {
  hrad::ElementHierarchy h(cornell());
  h.subdivide_uniform(cornell().total_area() / 100.0);
  const std::vector<hrad::NodeId> leaves = h.all_leaves();
  hrad::Effects effects;
  effects.visibility = false;
  const hrad::FormFactorEvaluator ev(cornell(), effects, nullptr, 16,
                                     static_cast<hrad::FormFactorKernel>(state.range(0)));
  const std::size_t n = std::min<std::size_t>(leaves.size(), 200);
  for (auto _ : state) {
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        const auto& a = h.node(leaves[i]);
        const auto& b = h.node(leaves[j]);
        sum += ev.estimate(a.polygon(), a.patch, b.polygon(), b.patch).value;
      }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["kernel_calls"] = static_cast<double>(ev.evaluations());
}
BENCHMARK(BM_KernelPairs)
    ->Arg(static_cast<int>(hrad::FormFactorKernel::kAnalytic))
    ->Arg(static_cast<int>(hrad::FormFactorKernel::kPointContour))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// A shelf board's visible fraction of an upright `gap` millimetres from it, under the next board:
// 1000 independent 64-pair estimates. At 5 mm the pair is closer than its size and its source
// points follow the solid angle from each board point; at 3 m (the board shaded alike by a longer
// one above), uniform by area. seconds_per_ray: sampling and the segment test.
void BM_PairVisibility(benchmark::State& state) {
  const double gap = state.range(0) * 1e-3, depth = 0.4;
  hrad::Scene s;
  hrad::Material m;
  m.name = "grey";
  m.reflectance = hrad::Rgb::Constant(0.5);
  s.materials.push_back(m);
  const auto add = [&s](std::vector<hrad::Vec3> v) {
    hrad::Patch p;
    p.vertices = std::move(v);
    const hrad::Vec3 n = (p.vertices[1] - p.vertices[0]).cross(p.vertices[2] - p.vertices[0]);
    p.normal = n.normalized();
    p.area = n.norm();
    p.material = 0;
    p.face = static_cast<int>(s.faces.size());
    s.faces.push_back({"f", 0, 0, p.area, {static_cast<int>(s.patches.size())}});
    s.patches.push_back(p);
  };
  add({{gap, 0, 0}, {gap + depth, 0, 0}, {gap + depth, 1, 0}, {gap, 1, 0}});  // board, up
  add({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}});                          // upright, +x
  // The next board (down), reaching the upright's 5 mm off, so that the far pair is shaded alike.
  add({{0.005, 0, 0.3}, {0.005, 1, 0.3}, {gap + depth, 1, 0.3}, {gap + depth, 0, 0.3}});
  const auto visibility = hrad::make_visibility(s);
  const hrad::Effects effects;
  const hrad::FormFactorEvaluator ev(s, effects, visibility.get(), 64, hrad::FormFactorKernel::kAnalytic);
  double sum = 0.0;
  for (auto _ : state)
    for (std::uint64_t k = 1; k <= 1000; ++k)
      sum += ev.pair_visibility(s.patches[0].vertices, 0, s.patches[1].vertices, 1, nullptr, 64, k).fraction;
  const double rays = static_cast<double>(ev.work().segment_queries);
  state.counters["rays"] = rays;
  state.counters["seconds_per_ray"] =
      benchmark::Counter(rays, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["mean_fraction"] = sum / (1000.0 * static_cast<double>(state.iterations()));
}
BENCHMARK(BM_PairVisibility)->Arg(5)->Arg(3000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
