// Scale: hierarchical radiosity on generated office rooms (hrad scene generate) of increasing size,
// clustered (Smits, Arvo & Greenberg 1994) against plain HSA (every pair of input polygons linked
// first), and one thread against two. Time and links as counters; one iteration each (a 16k solve
// takes minutes).
//   build-x/bin/scale_benchmark --benchmark_counters_tabular=true
//   build-x/bin/scale_benchmark --benchmark_filter='Clustered/(1000|4000|16000)/'
#include <benchmark/benchmark.h>

#include <map>

#include "hrad/experiments/scene_generator.h"
#include "hrad/solvers/solve.h"

namespace {

const hrad::Scene& office(int polygons) {
  static std::map<int, hrad::Scene> scenes;
  auto it = scenes.find(polygons);
  if (it == scenes.end()) it = scenes.emplace(polygons, hrad::to_scene(hrad::generate_scene({polygons, 1}))).first;
  return it->second;
}

void run(benchmark::State& state, hrad::Clustering clustering, int threads) {
  const hrad::Scene& scene = office(static_cast<int>(state.range(0)));
  hrad::SolveOptions o;
  o.method = hrad::Method::kHierarchical;
  o.clustering = clustering;
  o.threads = threads;
  hrad::SolveSummary summary;
  for (auto _ : state) {
    hrad::Solution solution;
    summary = hrad::solve(scene, o, &solution);
    benchmark::DoNotOptimize(solution.face_radiosity.data());
  }
  state.counters["polygons"] = static_cast<double>(scene.patches.size());
  state.counters["elements"] = static_cast<double>(summary.elements);
  state.counters["links"] = static_cast<double>(summary.links);
  state.counters["kernel_calls"] = static_cast<double>(summary.form_factor_evaluations);
  state.counters["iterations"] = summary.iterations;
  state.counters["peak_MB"] = static_cast<double>(summary.peak_memory_bytes) / 1e6;
  auto figure = [&](const char* name) {
    const auto f = summary.figures.find(name);
    return f == summary.figures.end() ? 0.0 : f->second;
  };
  state.counters["far_links"] = figure("far_field_links");
  state.counters["link_MB"] = figure("link_bytes") / 1e6;
  for (const auto& [phase, seconds] : summary.seconds)
    if (phase == "refine") state.counters["refine_s"] = seconds;
  if (summary.termination != hrad::Termination::kConverged) state.SkipWithError(summary.message.c_str());
}

void BM_Clustered(benchmark::State& state) { run(state, hrad::Clustering::kOn, 0); }
void BM_Unclustered(benchmark::State& state) { run(state, hrad::Clustering::kOff, 0); }
void BM_ClusteredOneThread(benchmark::State& state) { run(state, hrad::Clustering::kOn, 1); }
void BM_ClusteredTwoThreads(benchmark::State& state) { run(state, hrad::Clustering::kOn, 2); }

}  // namespace

BENCHMARK(BM_Clustered)->Arg(250)->Arg(1000)->Arg(4000)->Arg(16000)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_Unclustered)->Arg(250)->Arg(1000)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_ClusteredOneThread)->Arg(1000)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_ClusteredTwoThreads)->Arg(1000)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK_MAIN();
