// What accuracy costs in time: each method run over its accuracy parameter on one scene, every
// run judged against one reference on the same fixed surface samples (analysis/error_metrics.h).
#pragma once

#include <functional>
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
  int iterations = 0;
  std::string termination;
  std::vector<double> change_per_iteration;
};

/// The reference every run is judged against: a full-matrix LU solve on a finer uniform mesh than
/// any full-matrix run of the sweep, with four times their visibility samples (so it shares the
/// kernels but no discretisation with the runs).
struct Reference {
  Solution solution;  ///< reflected part B - E
  /// With SweepOptions::final_gather: B - E gathered from `solution` at the error samples
  /// (patch_samples(scene, samples_per_patch), in order); runs are judged against these instead.
  std::vector<Rgb> gathered;
  double gather_seconds = 0.0;
  SolveSummary summary;
  nlohmann::json description;  ///< how it was made (method, max_area, elements, seconds, ...)
};

struct SweepOptions {
  /// Elements of the reference mesh (uniform, full matrix, LU). 0 = 4 x the finest full run.
  double reference_elements = 0.0;
  /// Element counts of the full-matrix and substructuring runs (max_area = total area / count).
  std::vector<double> element_counts = {64, 128, 256, 512, 1024};
  /// Shooting-patch counts of the substructuring patch-size runs (at the median element count).
  std::vector<double> patch_counts = {24, 48, 96, 192, 384};
  /// Hierarchical form-factor tolerances (aeps automatic) and smallest-area fractions of the total area
  /// (feps at its default).
  std::vector<double> feps_values = {0.3, 0.1, 0.03, 0.01, 0.003, 0.001};
  std::vector<double> aeps_fractions = {1e-2, 3e-3, 1e-3, 3e-4, 1e-4};
  int samples_per_patch = 256;
  /// Visibility point pairs per partly visible pair in every run (0 = the solvers' default); the
  /// reference uses four times as many.
  int visibility_samples = 0;
  /// Judge runs against the reference solution's final gather at the samples
  /// (experiments/final_gather.h) instead of its own field.
  bool final_gather = true;
  int threads = 0;
  /// Progress: (runs done, runs in all, what runs now).
  std::function<void(int, int, std::string_view)> progress;
};

/// The solution with each element's emission subtracted (B - E): the part a solver computes. Errors
/// are measured on it, so that an emitter's large, known E does not dominate the norms.
Solution reflected_part(const Scene& scene, Solution solution);

/// The settings of a sweep on `scene` (in run order).
std::vector<std::pair<Method, SweepSetting>> sweep_settings(const Scene& scene, const SweepOptions& options);

/// Solves the reference (see Reference).
Reference make_reference(const Scene& scene, const SweepOptions& options);

/// Runs every setting and measures its error against `reference`.
std::vector<SweepRow> run_sweep(const Scene& scene, const Reference& reference, const SweepOptions& options);

/// Ceres power-law fits per method: seconds ~ a n^b and links ~ c n^alpha over elements n, and for
/// the hierarchical feps runs error_l2 ~ k feps^beta; plus, per method and per field (constant:
/// "time_to_target_error", interpolated: "time_to_target_error_smooth"), the time to reach
/// `target_error` (log-log interpolation between the bracketing runs, or "not reached"), and the
/// full/hierarchical ratios ("speedup", "speedup_smooth"); where the runs do not bracket the target,
/// the ratio at the lowest error both reached ("speedup_at_common_error[_smooth]") and the fits'
/// extrapolation to the target, labelled as such ("speedup_extrapolated[_smooth]").
nlohmann::json sweep_fits(const std::vector<SweepRow>& rows, double target_error = 0.01);

/// The rows as CSV (header: method,parameter,value,elements,links,form_factor_evaluations,
/// visibility_queries,seconds,error_l2,error_linf,iterations,termination,error_l2_smooth,error_linf_smooth).
std::string sweep_csv(const std::vector<SweepRow>& rows);

nlohmann::json fit_json(const PowerLawFit& fit);

}  // namespace hrad
