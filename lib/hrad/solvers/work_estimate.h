// What a solve will cost, estimated from the scene and the options before any meshing, so that
// unbounded or absurd requests (--aeps 1e-300, --max-area 1e-4 on a room in millimetres) are refused
// in milliseconds with the estimate and the option to change, instead of running until killed or
// ending in std::bad_alloc.
//
//   full          n elements (uniform 1-to-4 splits down to max_area, uniform_elements()); n^2 / 2
//                 kernel calls (each gives both directions); memory: F and, for LU, one system
//                 matrix, 2 n^2 doubles.
//   substructure  N shooting patches (uniform splits to patch_area), n elements below them; n N
//                 kernel calls; memory: the n x N matrix.
//   hierarchical  at most total area / aeps leaves (no leaf is split below aeps), so at most 4/3 of
//                 that in nodes; links kLinksPerElement per element; kernel calls
//                 kEvaluationsPerLink per link. These two constants are rough averages, not bounds:
//                 the refinement's owner retunes them when the oracle changes.
// Partly visible pairs cost visibility_samples segment queries each; kPartlyVisibleShare of the
// kernel calls are assumed partly visible.
#pragma once

#include <string>

#include "hrad/core/scene.h"
#include "hrad/solvers/solve.h"

namespace hrad {

/// Hierarchical: links per element, an average over measured solves (the Cornell box at the
/// defaults: 518 elements, 26.5 k links, 51 per element; generated offices at the defaults: 186 per
/// element at 32 k polygons, 190 at 63 k), rounded up.
inline constexpr double kLinksPerElement = 200.0;
/// Hierarchical: kernel calls per link (refinement tries candidates it splits, then the leaf factors).
inline constexpr double kEvaluationsPerLink = 4.0;
/// Bytes per element (quadtree node, leaf mesh, radiosity arrays) and per hierarchical link: the
/// peak of the whole solve (the refinement's working set, links, gather operators) over its links,
/// measured on generated offices at the defaults (1.6 GB for 5.96 M links at 32 k polygons, 3.1 GB
/// for 12.0 M at 63 k: ~260 bytes a link).
inline constexpr double kBytesPerElement = 512.0;
inline constexpr double kBytesPerLink = 256.0;
/// Share of kernel calls that are partly visible and cost visibility_samples segment queries.
inline constexpr double kPartlyVisibleShare = 0.25;
/// More kernel calls than this, or more segment queries than kMaxSegmentQueries, is refused as
/// absurd (days of work on this kind of machine: ~3e5 pair factors and ~1e6 queries per second per core).
inline constexpr double kMaxFormFactors = 1e10;
inline constexpr double kMaxSegmentQueries = 1e12;
/// The largest --visibility-samples accepted (validate_options).
inline constexpr int kMaxVisibilitySamples = 65536;

struct WorkEstimate {
  double elements = 0.0;         ///< leaves expected (hierarchical: the upper bound)
  double interactions = 0.0;     ///< n^2, n N, or links
  double form_factors = 0.0;     ///< kernel calls
  double segment_queries = 0.0;  ///< visibility rays
  double bytes = 0.0;            ///< memory of the largest arrays
  std::string option;            ///< the option that sets the size, as the command line spells it
  double option_value = 0.0;     ///< its value in effect (automatic values resolved)
  std::string remedy;            ///< which way to change it ("raise --aeps")
};

/// The option that makes a solve of `method` smaller: "raise --aeps", "raise --max-area".
std::string_view smaller_work(Method method);

/// Elements after uniform 1-to-4 splits of every patch until each piece is <= max_area.
double uniform_elements(const Scene& scene, double max_area);

/// The estimate for options.method (automatic values resolved as the solvers resolve them).
WorkEstimate estimate_work(const Scene& scene, const SolveOptions& options);

/// Throws hrad::Error when `estimate` needs more than 80% of `available_bytes` (0 = unknown: no
/// memory check) or more than kMaxFormFactors kernel calls or kMaxSegmentQueries queries:
/// "hierarchical: about 2.7e+12 elements need 3.1e+03 TB and this machine has 25.3 GB: raise --aeps (now 1e-06)".
void check_work(const WorkEstimate& estimate, std::string_view method, double available_bytes);

}  // namespace hrad
