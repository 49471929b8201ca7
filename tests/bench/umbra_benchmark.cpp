// Brightness of umbras (tests/support/umbra_bias.h): on the bundled Cornell box, the leaves that see
// none of the light are lit only by interreflection, through links that may be coarse. A link gives
// its receiver a quadratic field through the receiver's points (the HSA push) or each leaf its own
// factor (the leaf push), and weighs its source's radiosity by a field over the source; where either
// field strays from the point kernel, umbra leaves gather light their own points do not see. This
// measures each umbra leaf against the final gather of the same solution at points across it.
// Counters: bias in percent per surface group, the largest single leaf's, and the elements.
// Arguments: aeps as total area / arg, and the push (0 = hsa, 1 = leaf).
//   build/bin/umbra_benchmark --benchmark_counters_tabular=true
// (aeps total/12000 gives about 5k elements, total/14000 about 6k; a few minutes a run.)
#include <benchmark/benchmark.h>

#include <string>

#include "hrad/io/obj_reader.h"
#include "hrad/solvers/solve.h"
#include "support/source_tree.h"
#include "support/umbra_bias.h"

namespace hrad {
namespace {

void BM_UmbraBias(benchmark::State& state) {
  const Scene scene = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  SolveOptions options;
  options.aeps = scene.total_area() / static_cast<double>(state.range(0));
  options.push = state.range(1) == 0 ? Push::kHsa : Push::kLeaf;
  options.visibility_samples = static_cast<int>(state.range(2));
  for (auto _ : state) {
    Solution s;
    solve(scene, options, &s);
    for (const auto& [name, g] : test::umbra_bias(scene, s)) {
      state.counters[name + "%"] = 100.0 * g.bias;
      state.counters[name + " leaf max%"] = 100.0 * g.worst;
    }
    state.counters["elements"] = static_cast<double>(s.faces.size());
  }
}
BENCHMARK(BM_UmbraBias)
    ->ArgsProduct({{4000, 12000, 14000}, {0, 1}, {kDefaultVisibilitySamples}})
    // The umbras' dependence on the partly visible links' samples.
    ->Args({4000, 0, 256})
    ->ArgNames({"total/aeps", "leaf_push", "samples"})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace
}  // namespace hrad

BENCHMARK_MAIN();
