// Hierarchical radiosity on the Cornell box: defaults, coarser and finer form-factor tolerances
// and BF refinement; the work each did (work_counters.h) as counters.
//   build/bin/hierarchical_benchmark --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>

#include "hrad/io/obj_reader.h"
#include "hrad/solvers/hierarchical.h"
#include "hrad/solvers/solve.h"
#include "support/source_tree.h"
#include "work_counters.h"

namespace {

const hrad::Scene& cornell_box() {
  static const hrad::Scene scene =
      hrad::read_obj_scene(hrad::test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  return scene;
}

void run(benchmark::State& state, const hrad::SolveOptions& options) {
  const hrad::Scene& scene = cornell_box();
  hrad::SolveSummary summary;
  for (auto _ : state) {
    hrad::Solution solution;
    summary = hrad::solve_hierarchical(scene, options, &solution);
    benchmark::DoNotOptimize(solution.face_radiosity.data());
  }
  hrad::bench::add_work_counters(state, summary);
}

void BM_CornellDefaults(benchmark::State& state) { run(state, hrad::SolveOptions{}); }

// Form-factor tolerance feps = 1 / range(0): 100 is the default (kAutoFeps = 0.01).
void BM_CornellFeps(benchmark::State& state) {
  hrad::SolveOptions o;
  o.feps = 1.0 / static_cast<double>(state.range(0));
  run(state, o);
}

// B*F tolerance as a fraction 1 / range(0) of the light's brightest channel.
void BM_CornellBfeps(benchmark::State& state) {
  hrad::SolveOptions o;
  double e = 0.0;
  for (const hrad::Material& m : cornell_box().materials) e = std::max(e, m.emission.maxCoeff());
  o.bfeps = e / static_cast<double>(state.range(0));
  run(state, o);
}

// Single-threaded, to compare with the parallel default (estimates run in parallel).
void BM_CornellDefaultsOneThread(benchmark::State& state) {
  hrad::SolveOptions o;
  o.threads = 1;
  run(state, o);
}

BENCHMARK(BM_CornellDefaults)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CornellDefaultsOneThread)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CornellFeps)->Arg(25)->Arg(50)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CornellBfeps)->Arg(500)->Arg(2000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
