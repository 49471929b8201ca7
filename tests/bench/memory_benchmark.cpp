// First touch of a large fresh array with ordinary pages against transparent huge pages
// (hrad/core/huge_page_allocator.h): the solvers' largest arrays (leaf factors, the full matrix)
// are written once after allocation, so the page faults of first touch are part of their cost.
//   build/bin/memory_benchmark --benchmark_counters_tabular=true
// The two rows are the solvers' BigVector (huge pages; resize() leaves doubles unwritten, so each page
// is touched once) and a std::vector (ordinary pages, zero-filled by resize() and then written).
// Compare the two rows of one run; bytes_per_second is per CPU second.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "hrad/core/huge_page_allocator.h"

namespace {

// Allocates state.range(0) MB and writes every double once, as the solvers fill their arrays.
template <class Allocator>
void first_touch(benchmark::State& state) {
  const std::size_t n = static_cast<std::size_t>(state.range(0)) * (std::size_t{1} << 20) / sizeof(double);
  for (auto _ : state) {
    std::vector<double, Allocator> v;
    v.resize(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = double(i);
    benchmark::DoNotOptimize(v.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * n * sizeof(double)));
}

void BM_FirstTouchOrdinaryPages(benchmark::State& state) { first_touch<std::allocator<double>>(state); }
void BM_FirstTouchHugePages(benchmark::State& state) { first_touch<hrad::HugePageAllocator<double>>(state); }

BENCHMARK(BM_FirstTouchOrdinaryPages)->Arg(256)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FirstTouchHugePages)->Arg(256)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
