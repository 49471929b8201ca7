// The work a solve did (solvers/work.h) as Google Benchmark counters, so that every benchmark
// reports what it measured in the same terms: gather terms per iteration, factors evaluated,
// rays, bytes held by the links. `links` counts both directions of each link.
#pragma once

#include <benchmark/benchmark.h>

#include "hrad/solvers/solve.h"

namespace hrad::bench {

inline void add_work_counters(benchmark::State& state, const SolveSummary& summary) {
  const Work& w = summary.work;
  state.counters["elements"] = static_cast<double>(summary.elements);
  state.counters["links"] = static_cast<double>(summary.links);
  state.counters["gather_terms"] = static_cast<double>(w.gather_terms);
  state.counters["point_factors"] = static_cast<double>(w.point_factor_evaluations);
  state.counters["form_factors"] = static_cast<double>(w.form_factor_evaluations);
  state.counters["rays"] = static_cast<double>(w.segment_queries);
  state.counters["shafts"] = static_cast<double>(w.shaft_queries);
  state.counters["candidates"] = static_cast<double>(w.candidate_pairs);
  state.counters["link_MB"] = static_cast<double>(w.link_bytes) / 1e6;
  state.counters["peak_MB"] = static_cast<double>(summary.peak_memory_bytes) / 1e6;
  state.counters["iterations"] = summary.iterations;
  for (const auto& [phase, seconds] : summary.seconds)
    if (phase == "refine") state.counters["refine_s"] = seconds;
}

}  // namespace hrad::bench
