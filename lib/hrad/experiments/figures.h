// The lecture's figures, measured (Lischinski, "Hierarchical Radiosity", lecture notes 2004):
//   1. form factors against elements: full matrix (n^2), substructuring (nN), hierarchical (links);
//   2. two surfaces meeting along an edge: hierarchical elements refined near the edge;
//   3. two surfaces far apart: k^2 factors (full) against 2k (substructuring) and HR's few links;
//   4. the N-body analogy: Barnes-Hut interactions per body against n - 1 for the direct sum;
//   5. Jacobi convergence of the three solvers;
//   6. the Cornell box by each method at (about) equal solve time, with error images.
// Each function computes rows (and images); tools/figures.cpp writes them as CSV and PNG.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "hrad/analysis/barnes_hut.h"
#include "hrad/analysis/error_metrics.h"
#include "hrad/core/image.h"
#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/solvers/solve.h"
#include "hrad/solvers/work.h"

namespace hrad {

using ProgressFn = std::function<void(std::string_view)>;

// ---- Figure 1: form factors against elements ---------------------------------------------------

struct CostRow {
  std::string method;     ///< full | substructure | hierarchical
  std::string parameter;  ///< what was varied: max_area (full, substructure) or aeps (hierarchical)
  double value = 0.0;
  std::size_t patches = 0;   ///< input patches N (the shooters of substructuring)
  std::size_t elements = 0;  ///< leaves n
  std::size_t links = 0;     ///< SolveSummary::links: n^2, n N, or directed hierarchical links
  Work work;                 ///< what the solve did, as it counted it (solvers/work.h)
  double seconds = 0.0;
};

/// The measures of work figure 1 fits against elements: a name and how it is read from a row.
struct CostMeasure {
  const char* name;
  double (*of)(const CostRow&);
};
/// factor_evaluations (element and point form factors the kernels evaluated), gather_terms (terms
/// one gather iteration touches), segment_queries (visibility rays), seconds.
std::span<const CostMeasure> cost_measures();

struct CostOptions {
  /// Full matrix: max_area = total area / count (the full matrix with visibility is the slow one).
  std::vector<double> element_counts = {16, 32, 64, 128, 256};
  /// Substructuring: max_area = total area / count.
  std::vector<double> substructure_counts = {16, 32, 64, 128, 256, 512, 1024};
  /// Hierarchical: aeps = total area * fraction, feps fixed (the lecture's "fixed accuracy").
  std::vector<double> aeps_fractions = {3e-2, 1e-2, 3e-3, 1e-3};
  double feps = 0.0;  ///< 0 = the solver's default
  int threads = 0;
};

std::vector<CostRow> cost_rows(const Scene& scene, const CostOptions& options, const ProgressFn& progress = {});
/// Header: method,parameter,value,patches,elements,links,element_factor_evaluations,
/// point_factor_evaluations,gather_terms,segment_queries,seconds.
std::string cost_csv(const std::vector<CostRow>& rows);
/// Per method and measure (cost_measures()): Ceres fit measure ~ a elements^b (null with fewer than
/// 3 distinct element counts or a measure that is 0 somewhere).
nlohmann::json cost_fits(const std::vector<CostRow>& rows);

// ---- Figure 2: two surfaces meeting along an edge ----------------------------------------------

struct EdgeElementRow {
  int element = 0, patch = 0;
  double distance = 0.0;  ///< from the element's centroid to the common edge (a segment)
  double area = 0.0;
  double size = 0.0;  ///< sqrt(area)
};

struct EdgeFigure {
  Solution solution;
  SolveSummary summary;
  Vec3 edge_a = Vec3::Zero(), edge_b = Vec3::Zero();  ///< the common edge of patches 0 and 1
  std::vector<EdgeElementRow> rows;
};

/// Solves `scene` (two patches sharing an edge) hierarchically with `options` and measures each
/// leaf's size against its distance to the common edge. hrad::Error when patches 0 and 1 share no edge.
EdgeFigure edge_figure(const Scene& scene, SolveOptions options);
/// Header: element,patch,distance,area,size.
std::string edge_csv(const EdgeFigure& figure);

// ---- Figure 3: two surfaces far apart ----------------------------------------------------------

struct FarRow {
  int k = 0;  ///< elements per surface of the uniform meshes (4^d)
  std::string method;
  std::size_t elements = 0;  ///< leaves of the whole scene
  /// Factors between the two surfaces, each direction counted: full 2 k^2 (k^2 element pairs),
  /// substructuring 2k (each element receives from the other patch), hierarchical its directed links.
  std::size_t cross_factors = 0;
  /// Interactions counted once per pair: full k^2, substructuring 2k (elements x other patch), HR link pairs.
  std::size_t cross_pairs = 0;
  std::uint64_t form_factor_evaluations = 0;
  double seconds = 0.0;
};

/// For each k: full and substructuring with max_area = patch area / k, and hierarchical with
/// aeps = patch area / k (the same finest element size) and `feps` (0 = default). Expects two patches.
std::vector<FarRow> far_rows(const Scene& scene, const std::vector<int>& ks, double feps = 0.0, int threads = 0,
                             const ProgressFn& progress = {});
/// Header: k,method,elements,cross_factors,cross_pairs,form_factor_evaluations,seconds.
std::string far_csv(const std::vector<FarRow>& rows);

// ---- Figure 4: the N-body analogy --------------------------------------------------------------

/// Header: n,theta,mean_interactions,max_interactions,naive_interactions,relative_force_error,seconds.
std::string barnes_hut_csv(const std::vector<BarnesHutSample>& samples);

// ---- Figure 5: convergence ---------------------------------------------------------------------

struct ConvergenceRun {
  std::string method;
  SolveSummary summary;
};

/// Full matrix with Jacobi (max_area = total / full_elements), substructuring (same max_area) and
/// hierarchical (defaults), each to `tolerance`.
std::vector<ConvergenceRun> convergence_runs(const Scene& scene, double full_elements, double tolerance,
                                             int threads = 0, const ProgressFn& progress = {});
/// Header: method,iteration,change (iteration from 1), one row per iteration.
std::string convergence_csv(const std::vector<ConvergenceRun>& runs);

// ---- Figure 6: equal time ----------------------------------------------------------------------

struct EqualTimeRun {
  std::string method;
  std::string parameter;  ///< the setting chosen to meet the time budget
  double value = 0.0;
  Solution solution;  ///< as solved (emission included)
  SolveSummary summary;
  ErrorMetrics error;  ///< of B - E against the reference's, emitters excluded
};

struct EqualTimeFigure {
  double budget_seconds = 0.0;  ///< the hierarchical solve's time at its default settings
  Solution reference;
  SolveSummary reference_summary;
  std::vector<EqualTimeRun> runs;  ///< full, substructure, hierarchical
};

struct EqualTimeOptions {
  double reference_elements = 256;  ///< full matrix LU reference: max_area = total area / this
  double first_elements = 64;       ///< the first calibration run's count (max_area = total / this)
  int samples_per_patch = 256;
  /// Calibration runs per method (each a solve) to meet the budget; the run closest to it is kept.
  int calibration_runs = 3;
  SolveOptions hierarchical;  ///< the run that sets the budget (method forced to hierarchical)
  int threads = 0;
};

EqualTimeFigure equal_time_figure(const Scene& scene, const EqualTimeOptions& options, const ProgressFn& progress = {});
/// Header: method,parameter,value,elements,links,seconds,budget_seconds,error_l2,error_linf,image,error_image.
std::string equal_time_csv(const EqualTimeFigure& figure);

struct EqualTimeImages {
  std::vector<Image> renders, errors;  ///< per run, in run order; same camera and exposure
  double error_hi = 0.0;               ///< the common colour-bar top of the error images
};
EqualTimeImages equal_time_images(const Scene& scene, const EqualTimeFigure& figure, int width, int height);

}  // namespace hrad
