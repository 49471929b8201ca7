// Form-factor kernels: throughput of point-to-quad and quad-to-quad, and the closed form against the
// adaptive quadrature reference at equal accuracy. Run on one core, e.g.
//   taskset -c 0 build/bin/formfactor_benchmark --benchmark_repetitions=3 --benchmark_report_aggregates_only
// and quote ratios from one run. The counter `rel_error` is the error against Howell's C-11;
// items_per_second is per CPU second (on a loaded machine wall time is longer).
// Targets: point-to-quad >= 10 M/s, quad-to-quad in general position >= 200 k/s.
// Where the time goes: point-to-quad, per edge one cross product, one square root, one fast_atan2
// and one division (the atan2 was half the time with the C library's); quad-to-quad in general
// position, 16 skew edge pairs whose Clausen-type remainder takes ~11.7 Gauss nodes each (about
// two thirds of the time), the closed-form logarithmic part the rest (its logs and atans computed
// once per edge and vertex, not per pair). Measured 2026-11-22 against the kernels before these
// changes, in one run on the shared machine (load 5.8): point-to-quad 121 -> 104 ns (9.6 M/s),
// quad-to-quad general 10.0 -> 4.75 us (210 k/s), other paths unchanged.
// Then point-to-quad alone (a quad path with the diagonals' normal and unrolled contour loops, all
// edges' roots and dots before the atan2 terms, clipping and refinement out of line; bit-identical
// results but for repeated vertices, now more accurate when refined): 105 -> 63.1 ns CPU,
// 9.5 -> 15.9 M/s (medians of 5, old binary at 5e6bff6 and new at 98cf015 back to back, load 6), with
//   taskset -c 0 build/bin/formfactor_benchmark --benchmark_filter=PointToQuad --benchmark_repetitions=5
// Then quad-to-quad in general position (the remainder's integrand as scalar quadratics in s, so a
// Gauss node is a few multiply-adds, one packed square root and one atan2 with the octant in plain
// double; one Gauss routine per order; each vertex-vertex logarithm once; contour tables on the
// stack): 4.997 -> 3.540 us and 4.872 -> 3.539 us CPU (1.41x and 1.38x; 200 -> 283 k/s), other
// quad-to-quad cases unchanged (medians of 3, old binary at 9540781 and new at 906e0e0 alternated
// twice, load 4.5; the old binary had measured 4.8 us on a quiet machine), with
//   taskset -c 0 build/bin/formfactor_benchmark --benchmark_filter=QuadToQuad --benchmark_repetitions=3
//     --benchmark_report_aggregates_only=true
// Contour sums move by at most 2e-16 of their magnitude (764 random pairs; node counts unchanged).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "hrad/formfactor/fast_atan2.h"
#include "hrad/formfactor/point_to_polygon.h"
#include "hrad/formfactor/polygon_to_polygon.h"
#include "hrad/formfactor/quadrature_form_factor.h"
#include "support/monte_carlo_form_factor.h"

namespace {

using hrad::Vec3;
using Polygon = std::vector<Vec3>;

Polygon unit_square_at(double z, bool facing_down) {
  Polygon p{{0, 0, z}, {1, 0, z}, {1, 1, z}, {0, 1, z}};
  if (facing_down) std::swap(p[1], p[3]);
  return p;
}

// Howell C-11 for a x b plates at distance c (double precision is enough at a = b = c = 1).
double howell_c11(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double t = std::log(std::sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y))) +
                   x * std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y)) +
                   y * std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) - x * std::atan(x) - y * std::atan(y);
  return 2.0 / (M_PI * x * y) * t;
}

// The inner loops' atan2: the C library's against fast_atan2 (both within ~1 ulp), independent calls.
template <bool kFast>
void BM_Atan2(benchmark::State& state) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> y(1024), x(1024);
  for (int i = 0; i < 1024; ++i) y[i] = std::abs(u(rng)), x[i] = u(rng);
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 1023;
    benchmark::DoNotOptimize(kFast ? hrad::detail::fast_atan2(y[k], x[k]) : std::atan2(y[k], x[k]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Atan2<false>)->Name("BM_Atan2_Library");
BENCHMARK(BM_Atan2<true>)->Name("BM_Atan2_Fast");

void BM_PointToQuad(benchmark::State& state) {
  const Polygon quad = unit_square_at(1.0, true);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-0.5, 1.5);
  std::vector<Vec3> points(1024);
  for (Vec3& p : points) p = Vec3(u(rng), u(rng), 0.0);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(hrad::point_to_polygon(points[i++ & 1023], Vec3::UnitZ(), quad));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_PointToQuad);

// Opposed unit squares at distance 1: parallel and perpendicular edges (elementary closed form).
void BM_QuadToQuad_Parallel(benchmark::State& state) {
  const Polygon a = unit_square_at(0.0, false), b = unit_square_at(1.0, true);
  double f = 0.0;
  for (auto _ : state) {
    f = hrad::polygon_to_polygon(a, b).from_to;
    benchmark::DoNotOptimize(f);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["rel_error"] = std::abs(f / howell_c11(1, 1, 1) - 1);
}
BENCHMARK(BM_QuadToQuad_Parallel);

// Random quads in general position (all 16 edge pairs skew), distance ~ size.
void BM_QuadToQuad_General(benchmark::State& state) {
  std::mt19937_64 rng(2);
  std::normal_distribution<double> g(0.0, 0.15);
  std::vector<std::pair<Polygon, Polygon>> pairs;
  for (int k = 0; k < 64; ++k) {
    Polygon a = unit_square_at(0.0, false), b = unit_square_at(1.0, true);
    // Rotate b a little about a random axis through its centre; jitter in-plane keeps it planar.
    const Vec3 axis = Vec3(0.8 + g(rng), 0.5 + g(rng), 0.2 + g(rng)).normalized();
    const Eigen::Matrix3d r = Eigen::AngleAxisd(0.4 + g(rng), axis).toRotationMatrix();
    for (Vec3& v : b) v = r * (v - Vec3(0.5, 0.5, 1.0)) + Vec3(0.5 + g(rng), 0.5 + g(rng), 1.2);
    pairs.emplace_back(a, b);
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& [a, b] = pairs[i++ & 63];
    benchmark::DoNotOptimize(hrad::polygon_to_polygon(a, b));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_QuadToQuad_General);

// Unit squares with a common edge at right angles (Howell C-14).
void BM_QuadToQuad_SharedEdge(benchmark::State& state) {
  const Polygon a{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const Polygon b{{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}};
  for (auto _ : state) benchmark::DoNotOptimize(hrad::polygon_to_polygon(a, b));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_QuadToQuad_SharedEdge);

// Opposed unit squares at distance/size = state.range(0): the far-field quadrature path.
void BM_QuadToQuad_Far(benchmark::State& state) {
  const double c = double(state.range(0));
  const Polygon a = unit_square_at(0.0, false), b = unit_square_at(c, true);
  double f = 0.0;
  for (auto _ : state) {
    f = hrad::polygon_to_polygon(a, b).from_to;
    benchmark::DoNotOptimize(f);
  }
  state.SetItemsProcessed(state.iterations());
  // Howell C-11 while it is accurate in double; beyond, the two-term expansion (exact to ~c^-4).
  const double exact = c <= 100 ? howell_c11(1, 1, c) : 1.0 / (M_PI * c * c) * (1.0 - 2.0 / (3.0 * c * c));
  state.counters["rel_error"] = std::abs(f / exact - 1);
}
BENCHMARK(BM_QuadToQuad_Far)->Arg(10)->Arg(1000)->Arg(1000000);

// The adaptive quadrature reference on the C-11 unit case at tolerance 10^-range(0): compare its time
// at the tolerance where rel_error matches BM_QuadToQuad_Parallel's.
void BM_QuadratureReference(benchmark::State& state) {
  const Polygon a = unit_square_at(0.0, false), b = unit_square_at(1.0, true);
  const double tol = std::pow(10.0, -double(state.range(0)));
  hrad::QuadratureFormFactor q;
  for (auto _ : state) {
    q = hrad::quadrature_form_factor(a, b, tol);
    benchmark::DoNotOptimize(q);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["rel_error"] = std::abs(q.value / howell_c11(1, 1, 1) - 1);
  state.counters["evaluations"] = double(q.evaluations);
}
BENCHMARK(BM_QuadratureReference)->Arg(6)->Arg(9)->Arg(12)->Unit(benchmark::kMillisecond);

void BM_MonteCarloReference(benchmark::State& state) {
  const Polygon a = unit_square_at(0.0, false), b = unit_square_at(1.0, true);
  hrad::MonteCarloFormFactor m;
  for (auto _ : state) {
    m = hrad::monte_carlo_form_factor(a, b, std::uint64_t(state.range(0)), 7);
    benchmark::DoNotOptimize(m);
  }
  state.counters["rel_error"] = std::abs(m.value / howell_c11(1, 1, 1) - 1);
  state.counters["rel_std_error"] = m.standard_error / m.value;
}
BENCHMARK(BM_MonteCarloReference)->Arg(1000000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
