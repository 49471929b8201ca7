// What every solver does around its own algorithm, written once: validate, build the visibility
// oracle, analyse the effects, make the form-factor evaluator, time phases, report progress,
// record iterations, and finally turn the element hierarchy into the Solution and the summary.
//
// A solver's shape (see full_matrix.cpp, substructuring.cpp):
//
//   SolveSummary solve_xxx(const Scene& scene, const SolveOptions& options, Solution* out) {
//     SolverContext ctx(scene, options, Method::kXxx);   // validates, effects, evaluator
//     ElementHierarchy h(scene);
//     { auto phase = ctx.phase("mesh"); h.subdivide_uniform(ctx.max_area()); }
//     ... ctx.evaluator().estimate(...) ...
//     while (...) { ...; if (ctx.record_iteration(change)) break; }
//     return ctx.finish(h, links, out);
//   }
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hrad/core/memory.h"
#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/core/stopwatch.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/solvers/effects.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/solvers/solve.h"
#include "hrad/solvers/work_estimate.h"

namespace hrad {

class Visibility;

/// Largest element area for `scene` when SolveOptions::max_area is 0: total area / kAutoElements.
double automatic_max_area(const Scene& scene);

class SolverContext {
 public:
  /// Validates `options` (hrad::Error before any work), limits TBB to options.threads, builds the
  /// visibility oracle when the effects may need it, analyses the effects (phase "effects") and
  /// makes the evaluator. Keeps references to `scene` and `options`: both must outlive it.
  SolverContext(const Scene& scene, const SolveOptions& options, Method method);
  ~SolverContext();
  SolverContext(const SolverContext&) = delete;
  SolverContext& operator=(const SolverContext&) = delete;

  const Scene& scene() const { return scene_; }
  const SolveOptions& options() const { return options_; }
  const Effects& effects() const { return summary_.effects; }
  const FormFactorEvaluator& evaluator() const { return *evaluator_; }
  /// Tells the evaluator which nodes of `h` the factors will be taken to
  /// (FormFactorEvaluator::set_sources()); before the first factor.
  void set_sources(const ElementHierarchy& h, const std::vector<NodeId>& sources);
  /// The oracle (null when effects().visibility is false and it was not needed for the analysis).
  const Visibility* visibility() const { return visibility_.get(); }
  /// options.max_area, or automatic_max_area(scene) when it is 0.
  double max_area() const;
  /// Channels to compute: 1 (then copy channel 0 to 1 and 2 with copy_gray()) or 3.
  int channels() const { return summary_.effects.color_channels; }
  Method method() const { return summary_.method; }
  /// What a phase ("mesh", "refine", ...) allocates, for an out-of-memory message: "the links of the refinement".
  std::string allocating_in(const std::string& phase) const;

  /// Times a phase from construction to destruction into summary.seconds (added to an existing
  /// entry of the same name).
  class Phase {
   public:
    Phase(SolverContext& ctx, std::string name)
        : ctx_(ctx), name_(std::move(name)), allocating_(ctx.allocating_in(name_), smaller_work(ctx.method())) {}
    ~Phase() { ctx_.add_seconds(name_, watch_.seconds()); }
    Phase(const Phase&) = delete;
    Phase& operator=(const Phase&) = delete;

   private:
    SolverContext& ctx_;
    std::string name_;
    AllocationScope allocating_;  ///< names the phase if it runs out of memory
    Stopwatch watch_;
  };
  Phase phase(std::string name) { return Phase(*this, std::move(name)); }
  void add_seconds(const std::string& name, double seconds);

  /// Sends one line to options.progress (if set).
  void progress(std::string_view line) const;

  /// Appends `change` (largest relative change of this iteration) to the summary and returns true
  /// when iterating should stop: converged (termination kConverged), out of iterations
  /// (kMaxIterations), or non-finite (kFailed); sets the message. Converged means the estimated
  /// error of the current iterate is below the tolerance: for an iteration that contracts the
  /// error by q per step, the remaining error is at most change q / (1 - q) (the tail of a
  /// geometric series), with q the largest of the last three ratios of successive changes (one
  /// ratio is noisy while the slowest mode takes over). The first iteration never converges
  /// unless nothing changed; q >= 1 (not contracting) never converges. Long runs get a progress
  /// line every few seconds with the iterations still needed (extrapolated from q) and their time.
  bool record_iteration(double change);
  /// For direct solves: termination kDirect with `message`.
  void set_direct(std::string message);
  /// For numerical failures: termination kFailed with `message`.
  void set_failed(std::string message);

  SolveSummary& summary() { return summary_; }
  /// The estimated error of the current iterate (see record_iteration()); +infinity until known.
  double estimated_error() const { return estimated_error_; }

  /// Finishes: counters from the evaluator, elements from `hierarchy`, links as given, phase
  /// "output" for hierarchy.to_solution() into `out` (if not null; with the leaves' radiosity at
  /// their points when given), peak memory, total seconds.
  SolveSummary finish(const ElementHierarchy& hierarchy, std::size_t links, Solution* out,
                      std::span<const std::array<Rgb, 9>> point_radiosity = {});

 private:
  const Scene& scene_;
  const SolveOptions& options_;
  void report_iteration(double change);

  Stopwatch total_;
  double first_iteration_at_ = 0.0, next_iteration_line_at_ = 0.0;
  SolveSummary summary_;
  double estimated_error_ = INFINITY;
  std::unique_ptr<Visibility> visibility_;
  std::unique_ptr<FormFactorEvaluator> evaluator_;
  struct ThreadLimit;
  std::unique_ptr<ThreadLimit> thread_limit_;
};

/// Copies channel 0 into channels 1 and 2 (for gray scenes solved with one channel).
inline void copy_gray(Rgb& value) { value[1] = value[2] = value[0]; }

/// The peak resident set of this process in bytes (Linux VmHWM), 0 if unknown.
std::size_t peak_memory_bytes();

}  // namespace hrad
