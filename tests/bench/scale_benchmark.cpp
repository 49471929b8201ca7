// Scale: hierarchical radiosity on generated scenes (hrad scene generate) of increasing size:
// offices (boxes on a floor), pillar halls (a grid of floor-to-ceiling pillars: many occluders in
// every shaft), warehouses (rows of shelving racks) and city blocks; clustered (Smits, Arvo & Greenberg 1994) against
// plain HSA (every pair of input polygons linked first), and one thread against two on a refine-dominated hall. The
// work done (work_counters.h) as counters, so that its growth with the polygons can be fitted beside the time; one
// iteration each (a 16k solve takes minutes). Each scene cut along its near faces (io/near_faces.h), as hrad solve
// reads the same scene's file.
//   build/bin/scale_benchmark --benchmark_counters_tabular=true
//   build/bin/scale_benchmark --benchmark_filter='Pillars/(1000|4000|16000)/'
#include <benchmark/benchmark.h>

#include <map>
#include <utility>

#include "hrad/experiments/scene_generator.h"
#include "hrad/io/near_faces.h"
#include "hrad/solvers/solve.h"
#include "work_counters.h"

namespace {

const hrad::Scene& generated(hrad::SceneLayout layout, int polygons) {
  static std::map<std::pair<int, int>, hrad::Scene> scenes;
  const std::pair<int, int> key{static_cast<int>(layout), polygons};
  auto it = scenes.find(key);
  if (it == scenes.end()) {
    hrad::SceneGeneratorOptions o;
    o.polygons = polygons;
    o.seed = 1;
    o.layout = layout;
    hrad::Scene scene = hrad::to_scene(hrad::generate_scene(o));
    hrad::cut_near_faces(scene);
    it = scenes.emplace(key, std::move(scene)).first;
  }
  return it->second;
}

void run(benchmark::State& state, hrad::SceneLayout layout, hrad::Clustering clustering, int threads) {
  const hrad::Scene& scene = generated(layout, static_cast<int>(state.range(0)));
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
  state.counters["polygons"] = static_cast<double>(scene.faces.size());
  state.counters["patches"] = static_cast<double>(scene.patches.size());
  hrad::bench::add_work_counters(state, summary);
  if (summary.termination != hrad::Termination::kConverged) state.SkipWithError(summary.message.c_str());
}

using hrad::Clustering;
using hrad::SceneLayout;
void BM_Office(benchmark::State& state) { run(state, SceneLayout::kOffice, Clustering::kOn, 0); }
void BM_Pillars(benchmark::State& state) { run(state, SceneLayout::kPillars, Clustering::kOn, 0); }
void BM_Shelves(benchmark::State& state) { run(state, SceneLayout::kShelves, Clustering::kOn, 0); }
void BM_City(benchmark::State& state) { run(state, SceneLayout::kCity, Clustering::kOn, 0); }
void BM_OfficeUnclustered(benchmark::State& state) { run(state, SceneLayout::kOffice, Clustering::kOff, 0); }
void BM_PillarsOneThread(benchmark::State& state) { run(state, SceneLayout::kPillars, Clustering::kOn, 1); }
void BM_PillarsTwoThreads(benchmark::State& state) { run(state, SceneLayout::kPillars, Clustering::kOn, 2); }

}  // namespace

BENCHMARK(BM_Office)
    ->Arg(250)
    ->Arg(1000)
    ->Arg(4000)
    ->Arg(16000)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();
BENCHMARK(BM_Pillars)->Arg(1000)->Arg(4000)->Arg(16000)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_Shelves)->Arg(1000)->Arg(4000)->Arg(16000)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_City)->Arg(1000)->Arg(4000)->Arg(16000)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_OfficeUnclustered)->Arg(250)->Arg(1000)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_PillarsOneThread)->Arg(4000)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_PillarsTwoThreads)->Arg(4000)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK_MAIN();
