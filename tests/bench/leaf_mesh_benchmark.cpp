// The element hierarchy's half-edge leaf mesh: building it from a scene (the one weld of the
// patches' corners), splitting leaves in place, balancing and copying the mesh out as a Solution.
// Each reports its work per second (patches welded, splits, leaves visited, faces written).
//   build/bin/leaf_mesh_benchmark --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <random>
#include <string>

#include "hrad/experiments/scene_generator.h"
#include "hrad/io/obj_reader.h"
#include "hrad/mesh/element_hierarchy.h"
#include "support/source_tree.h"

namespace {

const hrad::Scene& cornell_box() {
  static const hrad::Scene scene =
      hrad::read_obj_scene(hrad::test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  return scene;
}

double total_area(const hrad::Scene& s) {
  double a = 0.0;
  for (const hrad::Patch& p : s.patches) a += p.area;
  return a;
}

// Generated offices of range(0) polygons.
void BM_BuildFromOffice(benchmark::State& state) {
  hrad::SceneGeneratorOptions o;
  o.polygons = static_cast<int>(state.range(0));
  const hrad::Scene scene = hrad::to_scene(hrad::generate_scene(o));
  for (auto _ : state) {
    hrad::ElementHierarchy h(scene);
    benchmark::DoNotOptimize(h.size());
  }
  state.counters["patches/s"] =
      benchmark::Counter(static_cast<double>(scene.patches.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_BuildFromOffice)->Arg(1000)->Arg(32000)->Unit(benchmark::kMillisecond);

// The Cornell box split uniformly to about range(0) leaves.
void BM_SplitUniform(benchmark::State& state) {
  const hrad::Scene& scene = cornell_box();
  const double max_area = total_area(scene) / static_cast<double>(state.range(0));
  std::size_t splits = 0;
  for (auto _ : state) {
    hrad::ElementHierarchy h(scene);
    h.subdivide_uniform(max_area);
    splits = (h.size() - scene.patches.size()) / 4;
    benchmark::DoNotOptimize(h.nodes().data());
  }
  state.counters["splits"] = static_cast<double>(splits);
  state.counters["splits/s"] =
      benchmark::Counter(static_cast<double>(splits), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_SplitUniform)->Arg(4000)->Arg(64000)->Unit(benchmark::kMillisecond);

// The Cornell box split at random leaves (range(0) splits, fixed seed), then balanced.
void BM_Balance(benchmark::State& state) {
  const hrad::Scene& scene = cornell_box();
  hrad::ElementHierarchy refined(scene);
  std::mt19937 rng(1);
  for (int i = 0; i < state.range(0); ++i) {
    const std::vector<hrad::NodeId> leaves = refined.all_leaves();
    refined.split(leaves[std::uniform_int_distribution<std::size_t>(0, leaves.size() - 1)(rng)]);
  }
  std::size_t splits = 0;
  for (auto _ : state) {
    state.PauseTiming();
    hrad::ElementHierarchy h = refined;
    state.ResumeTiming();
    splits = h.balance();
    benchmark::DoNotOptimize(h.nodes().data());
  }
  state.counters["leaves"] = static_cast<double>(refined.all_leaves().size());
  state.counters["balance_splits"] = static_cast<double>(splits);
}
BENCHMARK(BM_Balance)->Arg(2000)->Unit(benchmark::kMillisecond);

// The leaves of the uniformly split Cornell box (about range(0)) copied out as a Solution.
void BM_ToSolution(benchmark::State& state) {
  const hrad::Scene& scene = cornell_box();
  hrad::ElementHierarchy h(scene);
  h.subdivide_uniform(total_area(scene) / static_cast<double>(state.range(0)));
  std::size_t faces = 0;
  for (auto _ : state) {
    const hrad::Solution s = h.to_solution();
    faces = s.faces.size();
    benchmark::DoNotOptimize(s.vertices.data());
  }
  state.counters["faces"] = static_cast<double>(faces);
  state.counters["faces/s"] =
      benchmark::Counter(static_cast<double>(faces), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ToSolution)->Arg(4000)->Arg(64000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
