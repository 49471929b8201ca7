// What accuracy costs in time: each method run over its accuracy parameter on one scene, every
// run judged against one reference on the same fixed surface samples (analysis/error_metrics.h).
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "hrad/analysis/power_law_fit.h"
#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/solvers/solve.h"

namespace hrad {

/// One run of a sweep: a method with one accuracy parameter set.
struct SweepSetting {
  std::string parameter;  ///< "max_area" | "patch_area" | "feps" | "aeps" | ...
  double value = 0.0;
  SolveOptions options;
};

struct SweepRow {
  std::string method, parameter;
  double value = 0.0;
  std::size_t elements = 0, links = 0;
  std::uint64_t form_factor_evaluations = 0, visibility_queries = 0;
  double seconds = 0.0;
  double error_l2 = 0.0, error_linf = 0.0;                ///< the constant element field (the unknowns)
  double error_l2_smooth = 0.0, error_linf_smooth = 0.0;  ///< the displayed, vertex-interpolated field
  /// The run's solution final-gathered at the error samples (B - E = rho H from its leaves,
  /// gather/leaf_gather.h, or through a hierarchical run's links, gather/link_gather.h), what a
  /// gathered image or a probe shows, against the reference's gather at the same samples. NaN where not measured (no
  /// gathered reference, or SweepOptions::gather_runs off).
  double error_l2_gathered = std::numeric_limits<double>::quiet_NaN();
  double error_linf_gathered = std::numeric_limits<double>::quiet_NaN();
  double gather_seconds = 0.0;    ///< the gather's own time (quadtrees and points), not in `seconds`
  std::uint64_t gather_work = 0;  ///< its point factors, visibility classifications and rays (GatherWork::total)
  int iterations = 0;
  std::string termination;
  std::vector<double> change_per_iteration;
};

/// The reference every run is judged against: a full-matrix LU solve on a uniform mesh (4 x the
/// finest full-matrix run's elements, at most kFinalGatherReferenceElements when final-gathered),
/// with four times the runs' visibility samples (so it shares the kernels but no discretisation
/// with the runs).
struct Reference {
  Solution solution;  ///< reflected part B - E
  /// With SweepOptions::final_gather: B - E gathered from `solution` at the error samples
  /// (patch_samples(scene, samples_per_patch), in order); runs are judged against these instead.
  std::vector<Rgb> gathered;
  double gather_seconds = 0.0;
  SolveSummary summary;
  nlohmann::json description;  ///< how it was made (method, max_area, elements, seconds, ...)
};

/// The default reference's element count (aimed at) when runs are judged against its final gather.
/// The gather, exact per point, converges much faster than the reference's own field (its element
/// error enters only through an integral), so the reference need not be finer than the runs it
/// judges, which an LU could not afford at the finest runs (8 n^2 bytes, O(n^3) time). Compare
/// references with `hrad sweep SCENE --reference-elements N` at two N.
inline constexpr double kFinalGatherReferenceElements = 4096;

struct SweepOptions {
  /// Elements of the reference mesh (uniform, full matrix, LU). 0 = 4 x the finest full run, at most
  /// kFinalGatherReferenceElements when the runs are judged against the reference's final gather.
  double reference_elements = 0.0;
  /// The full-matrix runs' linear solver. Gauss-Seidel, the classical choice (Cohen & Greenberg
  /// 1985), not LU: it converges in a few sweeps of n^2 terms where LU costs O(n^3), so the full
  /// matrix's time is its form factors, as in the lecture (the report's iterations and seconds show it).
  LinearSolver full_linear_solver = LinearSolver::kGaussSeidel;
  /// Element counts of the full-matrix and substructuring runs (max_area = total area / count).
  /// From 64 to 9000: on the Cornell box 2156 elements at 1024 and 17009 / 20666 at 7000 / 9000 (a
  /// uniform mesh quarters elements, so counts jump), the finest full-matrix runs near 1% of the
  /// reference (README, "Accuracy against time"); the finest needs 8 n^2 = 3.4 GB for F.
  std::vector<double> element_counts = {64, 256, 1024, 2560, 5120, 7000, 9000};
  /// Shooting-patch counts of the substructuring patch-size runs (at the median element count).
  std::vector<double> patch_counts = {24, 48, 96, 192, 384};
  /// Hierarchical form-factor tolerances (aeps automatic) and smallest-area fractions of the total area
  /// (feps at its default).
  std::vector<double> feps_values = {0.3, 0.1, 0.03, 0.01, 0.003, 0.001};
  std::vector<double> aeps_fractions = {1e-2, 1e-3, 1e-4, 5e-5, 3e-5, 2.5e-5, 2e-5, 1.5e-5};
  /// The smallest-area fraction of the feps runs (0 = the solver's automatic aeps).
  double feps_aeps_fraction = 0.0;
  /// The hierarchical runs' link operators: each feps and aeps setting runs once per push; rows of
  /// Push::kLeaf are labelled method "hierarchical_leaf".
  std::vector<Push> pushes = {Push::kHsa};
  /// The bases: every setting of the full matrix and substructuring, and each hierarchical feps and
  /// aeps setting with Push::kHsa, runs once per basis; rows of Basis::kLinear are labelled
  /// "full_linear", "substructure_linear" and "hierarchical_linear".
  std::vector<Basis> bases = {Basis::kConstant, Basis::kLinear};
  int samples_per_patch = 256;
  /// Visibility point pairs per partly visible pair in every run (0 = the solvers' default); the
  /// reference uses four times as many.
  int visibility_samples = 0;
  /// The hierarchical runs' --source-levels (SolveOptions::source_levels).
  int source_levels = 0;
  /// ... near bright lamps only (SolveOptions::source_levels_near_lamps; `--source-levels auto`).
  bool source_levels_near_lamps = false;
  /// Judge runs against the reference solution's final gather at the samples
  /// (experiments/final_gather.h) instead of its own field.
  bool final_gather = true;
  /// Also final-gather every run at the samples (SweepRow::error_l2_gathered), when the reference is
  /// gathered; the gather's Barnes-Hut tolerance (gather/leaf_gather.h) and, per partly visible
  /// leaf, the runs' visibility samples (64 when visibility_samples is 0).
  bool gather_runs = true;
  double gather_tolerance = 1e-2;
  /// Hierarchical runs gather through their links (gather/link_gather.h); false: over every patch
  /// like the other methods (gather/leaf_gather.h).
  bool gather_through_links = true;
  int threads = 0;
  /// Progress: (runs done, runs in all, what runs now).
  std::function<void(int, int, std::string_view)> progress;
  /// Progress inside each solve, the reference's included (SolveOptions::progress): long phases
  /// (a fine full matrix's form factors) print lines with an estimate of the time left.
  std::function<void(std::string_view)> solve_progress;
};

/// The solution with each element's emission subtracted (B - E): the part a solver computes. Errors
/// are measured on it, so that an emitter's large, known E does not dominate the norms.
Solution reflected_part(const Scene& scene, Solution solution);

/// The settings of a sweep on `scene` (in run order).
std::vector<std::pair<Method, SweepSetting>> sweep_settings(const Scene& scene, const SweepOptions& options);

/// The element count the reference aims at (SweepOptions::reference_elements, or its default).
double reference_elements_aimed(const SweepOptions& options);

/// Solves the reference (see Reference).
Reference make_reference(const Scene& scene, const SweepOptions& options);

/// Runs every setting and measures its error against `reference`. A run the solver refuses (an
/// hrad::Error, e.g. a full matrix larger than memory) is left out with a line on the progress.
std::vector<SweepRow> run_sweep(const Scene& scene, const Reference& reference, const SweepOptions& options);

/// Ceres power-law fits per method: seconds ~ a n^b and links ~ c n^alpha over elements n, and for
/// the hierarchical feps runs error_l2 ~ k feps^beta; plus, per method and per field (constant:
/// "time_to_target_error", interpolated: "time_to_target_error_smooth"), the time to reach
/// `target_error` (log-log interpolation between the bracketing runs, or "not reached"), and the
/// full/hierarchical ratios ("speedup", "speedup_smooth"); where the runs do not bracket the target,
/// the ratio at the lowest error both reached ("speedup_at_common_error[_smooth]") and the fits'
/// extrapolation to the target, labelled as such ("speedup_extrapolated[_smooth]"). The gathered
/// field ("_gathered": error_l2_gathered, the time seconds + gather_seconds) is fitted the same way
/// where the rows measured it.
nlohmann::json sweep_fits(const std::vector<SweepRow>& rows, double target_error = 0.01);

/// The rows as CSV (header: method,parameter,value,elements,links,form_factor_evaluations,
/// visibility_queries,seconds,error_l2,error_linf,iterations,termination,error_l2_smooth,error_linf_smooth,
/// error_l2_gathered,error_linf_gathered,gather_seconds,gather_work).
std::string sweep_csv(const std::vector<SweepRow>& rows);

nlohmann::json fit_json(const PowerLawFit& fit);

}  // namespace hrad
