// What a solve did, counted where it was done: the quantities the cost fits and figures use.
#pragma once

#include <cstdint>

namespace hrad {

struct Work {
  /// Terms one gather iteration touches (each multiplies a factor by a radiosity), counted by the
  /// link operator when it is built from what it stores.
  std::uint64_t gather_terms = 0;
  /// Point-to-polygon factors evaluated (refinement oracle, leaf factors, Gauss-point kernel).
  std::uint64_t point_factor_evaluations = 0;
  /// Element-to-element factors (analytic kernel calls, Gauss-point kernel calls, sampled cluster
  /// factors): one per call, whatever it cost inside.
  std::uint64_t form_factor_evaluations = 0;
  /// Segments tested for occlusion (rays).
  std::uint64_t segment_queries = 0;
  /// Shafts classified (pairs and point-to-polygon cones).
  std::uint64_t shaft_queries = 0;
  /// Bytes held by the link operator(s) at the end of the solve.
  std::uint64_t link_bytes = 0;
  /// Candidate pairs the refinement examined (hierarchical only).
  std::uint64_t candidate_pairs = 0;
};

}  // namespace hrad
