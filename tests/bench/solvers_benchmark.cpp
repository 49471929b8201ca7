// Full matrix vs substructuring on the bundled Cornell box at their defaults, and the two
// form-factor kernels on the same element pairs. Run: build/bin/solvers_benchmark
#include <benchmark/benchmark.h>

#include <string>

#include "hrad/io/obj_reader.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/effects.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/solvers/solve.h"
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

}  // namespace

BENCHMARK_MAIN();
