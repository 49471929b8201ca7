// Pair throughput of the view-factor matrix (pair_exchange(): classification, closed form,
// sampled visible fraction) on a generated urban scene, and the whole matrix with the large-model options.
#include <benchmark/benchmark.h>

#include <map>

#include "hrad/core/rng.h"
#include "hrad/experiments/urban_generator.h"
#include "hrad/viewfactors/view_factor_matrix.h"
#include "hrad/visibility/visibility.h"

namespace hrad {
namespace {

const Scene& urban(int facets) {
  static std::map<int, Scene> scenes;
  auto it = scenes.find(facets);
  if (it == scenes.end()) it = scenes.emplace(facets, to_scene(generate_urban({facets, 1}))).first;
  return it->second;
}

void BM_UrbanPairs(benchmark::State& state) {
  const Scene& s = urban(static_cast<int>(state.range(0)));
  const auto visibility = make_visibility(s, VisibilityOptions{.exact_shaft_contacts = true});
  Effects effects;
  effects.visibility = visibility->scene_has_occlusion();
  const FormFactorEvaluator ev(s, effects, visibility.get(), 64, FormFactorKernel::kAnalytic);
  detail::Rng rng(3);
  std::int64_t pairs = 0;
  for (auto _ : state) {
    const int p = static_cast<int>(rng.below(s.patches.size())), q = static_cast<int>(rng.below(s.patches.size()));
    if (p == q) continue;
    benchmark::DoNotOptimize(pair_exchange(ev, p, q, PairExchangeOptions{}));
    ++pairs;
  }
  state.SetItemsProcessed(pairs);
}
BENCHMARK(BM_UrbanPairs)->Arg(2000)->Unit(benchmark::kMicrosecond);

// The whole matrix with a threshold; the second argument 1 also samples far pairs (sample_below)
// without shaft tests, the large-model setting.
void BM_UrbanMatrix(benchmark::State& state) {
  const Scene& s = urban(static_cast<int>(state.range(0)));
  ViewFactorOptions o;
  o.threshold = 1e-5;
  o.row_error = 0.01;
  if (state.range(1) != 0) o.sample_below = 1e-3;
  for (auto _ : state) benchmark::DoNotOptimize(compute_view_factors(s, face_units(s), o).nonzeros());
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(s.patches.size() * (s.patches.size() - 1) / 2));
}
BENCHMARK(BM_UrbanMatrix)->Args({500, 0})->Args({500, 1})->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace hrad

BENCHMARK_MAIN();
