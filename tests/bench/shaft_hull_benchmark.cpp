// The shaft's side facets (shaft_hull.h) against CGAL's convex_hull_3 of the same eight corners:
// two facing quads at random offsets, as the classifier meets them. Per call:
//
//   build/bin/shaft_hull_benchmark
#include <benchmark/benchmark.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_3.h>

#include <array>
#include <random>
#include <vector>

#include "hrad/visibility/shaft_hull.h"
#include "support/epick_shaft_ops.h"

namespace hrad {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P = K::Point_3;

using EpickOps = test::EpickShaftOps;

/// Pairs of unit-ish quads: one on z = 0, one facing it from above, tilted.
std::vector<std::vector<P>> quad_pairs() {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::vector<P>> sets;
  for (int s = 0; s < 1024; ++s) {
    const double x0 = u(rng), y0 = u(rng), x1 = u(rng), y1 = u(rng), z = 1.0 + u(rng), tilt = 0.3 * u(rng);
    sets.push_back({P(x0, y0, 0), P(x0 + 0.3, y0, 0), P(x0 + 0.3, y0 + 0.3, 0), P(x0, y0 + 0.3, 0),
                    P(x1, y1, z), P(x1, y1 + 0.3, z), P(x1 + 0.3, y1 + 0.3, z + tilt), P(x1 + 0.3, y1, z + tilt)});
  }
  return sets;
}

void BM_ShaftFacetsEnumerated(benchmark::State& state) {
  const auto sets = quad_pairs();
  std::size_t i = 0, facets = 0;
  for (auto _ : state) {
    const auto& pts = sets[i++ % sets.size()];
    facets += detail::shaft_side_facets<EpickOps>(std::span<const P>(pts), 4).size();
  }
  benchmark::DoNotOptimize(facets);
}
BENCHMARK(BM_ShaftFacetsEnumerated);

// The triangulated hull only; grouping its triangles by plane and keeping those through points of
// both quads (what the shaft needs) would come on top.
void BM_ShaftFacetsCgalConvexHull(benchmark::State& state) {
  const auto sets = quad_pairs();
  std::size_t i = 0, faces_total = 0;
  std::vector<P> vertices;
  std::vector<std::array<std::size_t, 3>> faces;
  for (auto _ : state) {
    const auto& pts = sets[i++ % sets.size()];
    vertices.clear();
    faces.clear();
    CGAL::convex_hull_3(pts.begin(), pts.end(), vertices, faces);
    faces_total += faces.size();
  }
  benchmark::DoNotOptimize(faces_total);
}
BENCHMARK(BM_ShaftFacetsCgalConvexHull);

}  // namespace
}  // namespace hrad

BENCHMARK_MAIN();
