// Brightness of umbras (tests/support/umbra_bias.h): on the bundled Cornell box, the leaves that see
// none of the light are lit only by interreflection, through links that may be coarse. A link gives
// its receiver a quadratic field through the receiver's points (the HSA push) or each leaf its own
// factor (the leaf push), and weighs its source's radiosity by a field over the source; where either
// field strays from the point kernel, umbra leaves gather light their own points do not see. This
// measures each umbra leaf against the final gather of the same solution at points across it.
// The partly visible links' visible fractions are sampled, so a region's bias is a random variable:
// each case solves with several sample streams (SolveOptions::seed 0, 1, ...) and reports the mean
// over them (the bias) and their standard deviation (the noise of one solve).
// Counters: per surface group the mean bias in percent, its standard deviation over the seeds
// ("sd%"), the largest single leaf's over all seeds, and the elements (seed 0).
// Arguments: aeps as total area / arg, the push (0 = hsa, 1 = leaf), --visibility-samples, seeds.
//   build/bin/umbra_benchmark --benchmark_counters_tabular=true
// (aeps total/4000 gives about 2k elements, total/14000 about 6k; the 6k cases take about ten
// minutes each.)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

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
  const int seeds = static_cast<int>(state.range(3));
  for (auto _ : state) {
    std::map<std::string, std::vector<double>> bias;
    std::map<std::string, double> worst;
    for (int seed = 0; seed < seeds; ++seed) {
      options.seed = static_cast<std::uint64_t>(seed);
      Solution s;
      solve(scene, options, &s);
      for (const auto& [name, g] : test::umbra_bias(scene, s)) {
        bias[name].push_back(g.bias);
        worst[name] = std::max(worst[name], g.worst);
      }
      if (seed == 0) state.counters["elements"] = static_cast<double>(s.faces.size());
    }
    for (const auto& [name, b] : bias) {
      double mean = 0.0, squares = 0.0;
      for (const double x : b) mean += x / static_cast<double>(b.size());
      for (const double x : b) squares += (x - mean) * (x - mean);
      state.counters[name + "%"] = 100.0 * mean;
      state.counters[name + " sd%"] =
          b.size() > 1 ? 100.0 * std::sqrt(squares / static_cast<double>(b.size() - 1)) : 0.0;
      state.counters[name + " leaf max%"] = 100.0 * worst[name];
    }
  }
}
BENCHMARK(BM_UmbraBias)
    ->ArgsProduct({{4000, 14000}, {0, 1}, {kDefaultVisibilitySamples}, {4}})
    // The umbras' dependence on the partly visible links' samples.
    ->Args({4000, 0, 256, 4})
    ->ArgNames({"total/aeps", "leaf_push", "samples", "seeds"})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

}  // namespace
}  // namespace hrad

BENCHMARK_MAIN();
