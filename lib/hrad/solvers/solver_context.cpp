#include "hrad/solvers/solver_context.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "hrad/core/progress.h"
#include "hrad/visibility/visibility.h"

namespace hrad {

struct SolverContext::ThreadLimit {
  explicit ThreadLimit(int threads)
      : control(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads)) {}
  tbb::global_control control;
};

double automatic_max_area(const Scene& scene) { return scene.total_area() / kAutoElements; }

SolverContext::SolverContext(const Scene& scene, const SolveOptions& options, Method method)
    : scene_(scene), options_(options) {
  validate_options(options);
  summary_.method = method;
  summary_.used = options;
  summary_.used.progress = nullptr;
  summary_.patches = scene.patches.size();
  if (options.threads > 0) thread_limit_ = std::make_unique<ThreadLimit>(options.threads);
  {
    auto p = phase("effects");
    const bool may_need_visibility =
        options.effects == EffectsMode::kAll || options.irradiance || !scene_has_no_reflection(scene);
    if (may_need_visibility) visibility_ = make_visibility(scene);
    summary_.effects = analyse_effects(scene, options.effects, visibility_.get(), options.irradiance);
  }
  evaluator_ = std::make_unique<FormFactorEvaluator>(scene, summary_.effects, visibility_.get(),
                                                     options.visibility_samples, options.kernel, options.seed);
}

SolverContext::~SolverContext() = default;

void SolverContext::set_sources(const ElementHierarchy& h, const std::vector<NodeId>& sources) {
  std::vector<std::span<const Vec3>> polygons;
  std::vector<int> patches;
  for (const NodeId id : sources) {
    polygons.push_back(h.node(id).polygon());
    patches.push_back(h.node(id).patch);
  }
  evaluator_->set_sources(polygons, patches);
}

double SolverContext::max_area() const {
  return options_.max_area > 0.0 ? options_.max_area : automatic_max_area(scene_);
}

void SolverContext::add_seconds(const std::string& name, double seconds) {
  for (auto& [n, s] : summary_.seconds)
    if (n == name) {
      s += seconds;
      return;
    }
  summary_.seconds.emplace_back(name, seconds);
}

std::string SolverContext::allocating_in(const std::string& phase) const {
  // The largest arrays each phase makes.
  if (phase == "mesh") return "the elements";
  if (phase == "form_factors") return "the form-factor matrix";
  if (phase == "clusters") return "the cluster tree";
  if (phase == "refine") return "the links of the refinement";
  if (phase == "links") return "the link operators";
  if (phase == "closure") return "the send closure's coefficients";
  if (phase == "solve")
    return method() == Method::kFull && options_.linear_solver == LinearSolver::kLu ? "the LU factors of the system"
                                                                                    : "the radiosity arrays";
  if (phase == "output") return "the solution's leaf mesh";
  return fmt::format("the {} phase", phase);
}

void SolverContext::progress(std::string_view line) const {
  if (options_.progress) options_.progress(line);
}

bool SolverContext::record_iteration(double change) {
  ++summary_.iterations;
  summary_.change_per_iteration.push_back(change);
  if (!std::isfinite(change)) {
    set_failed(fmt::format("non-finite radiosity at iteration {}", summary_.iterations));
    return true;
  }
  const std::vector<double>& history = summary_.change_per_iteration;
  const std::size_t k = history.size();
  double rate = NAN;
  if (k >= 2) {
    rate = 0.0;
    for (std::size_t i = std::max<std::size_t>(1, k >= 3 ? k - 3 : 1); i < k; ++i)
      rate = std::max(rate, history[i - 1] > 0.0 ? history[i] / history[i - 1] : 0.0);
  }
  estimated_error_ = change == 0.0 ? 0.0 : (rate < 1.0 ? change * rate / (1.0 - rate) : INFINITY);
  if (estimated_error_ < options_.tolerance) {
    summary_.termination = Termination::kConverged;
    summary_.message = fmt::format(
        "converged in {} iterations (estimated relative error {:.3g} < tolerance {:.3g}; last change {:.3g}, "
        "contraction {:.3g} per iteration)",
        summary_.iterations, estimated_error_, options_.tolerance, change, std::isfinite(rate) ? rate : 0.0);
    return true;
  }
  if (summary_.iterations >= options_.max_iterations) {
    summary_.termination = Termination::kMaxIterations;
    summary_.message = fmt::format(
        "not converged: {} iterations reached with estimated relative error {:.3g} >= tolerance {:.3g} (last change "
        "{:.3g})",
        summary_.iterations, estimated_error_, options_.tolerance, change);
    return true;
  }
  report_iteration(change);
  return false;
}

void SolverContext::report_iteration(double change) {
  // A line every progress_interval_seconds of iterating (none for a solve that converges sooner),
  // with the iterations still needed at the geometric rate of the last kRateWindow iterations.
  const double interval = options_.progress_interval_seconds;
  constexpr int kRateWindow = 20;
  const int k = summary_.iterations;
  if (k == 1) {
    first_iteration_at_ = total_.seconds();
    next_iteration_line_at_ = first_iteration_at_ + interval;
    return;
  }
  const double now = total_.seconds();
  if (now < next_iteration_line_at_) return;
  next_iteration_line_at_ = now + interval;
  const std::vector<double>& changes = summary_.change_per_iteration;
  const int back = std::min(kRateWindow, k - 1);
  const std::optional<double> left =
      iterations_left(changes[static_cast<std::size_t>(k - 1 - back)], change, back, options_.tolerance);
  std::string line =
      fmt::format("iteration {}: relative change {:.3g} (tolerance {:.3g})", k, change, options_.tolerance);
  if (left) {
    const double seconds_per_iteration = (now - first_iteration_at_) / (k - 1);
    const double capped = std::min(*left, static_cast<double>(options_.max_iterations - k));
    line +=
        fmt::format(", about {:.0f} more iterations ({}){}", capped, format_duration(capped * seconds_per_iteration),
                    capped < *left ? " until --max-iterations" : "");
  }
  progress(line);
}

void SolverContext::set_direct(std::string message) {
  summary_.termination = Termination::kDirect;
  summary_.message = std::move(message);
}

void SolverContext::set_failed(std::string message) {
  summary_.termination = Termination::kFailed;
  summary_.message = std::move(message);
}

SolveSummary SolverContext::finish(const ElementHierarchy& hierarchy, std::size_t links, Solution* out,
                                   std::span<const std::array<Rgb, 9>> point_radiosity) {
  std::size_t leaves = 0;
  for (const ElementNode& n : hierarchy.nodes()) leaves += n.is_leaf() ? 1 : 0;
  summary_.elements = leaves;
  summary_.links = links;
  summary_.form_factor_evaluations = evaluator_->evaluations();
  summary_.visibility_queries = evaluator_->visibility_queries();
  const Work counted = evaluator_->work();
  summary_.work.point_factor_evaluations = counted.point_factor_evaluations;
  summary_.work.form_factor_evaluations = counted.form_factor_evaluations;
  summary_.work.shaft_queries = counted.shaft_queries;
  summary_.work.segment_queries = counted.segment_queries;
  summary_.figures["culled_pairs"] = static_cast<double>(evaluator_->culled_pairs());
  if (visibility_) {
    summary_.figures["segment_queries"] =
        static_cast<double>(visibility_->counters().segment_queries.load());
  }
  if (out != nullptr) {
    auto p = phase("output");
    *out = hierarchy.to_solution(point_radiosity);
    if (options_.basis == Basis::kLinear && !point_radiosity.empty()) {
      // The leaves' linear fields by their corner values (the first points; faces are in leaf order).
      const std::vector<NodeId> leaves = hierarchy.all_leaves();
      out->face_field.resize(leaves.size());
      for (std::size_t f = 0; f < leaves.size(); ++f) {
        const ElementNode& e = hierarchy.node(leaves[f]);
        ElementField& field = out->face_field[f];
        field.corners = e.vertex_count;
        for (int k = 0; k < e.vertex_count; ++k) {
          field.x[static_cast<std::size_t>(k)] = e.polygon()[static_cast<std::size_t>(k)];
          field.radiosity[static_cast<std::size_t>(k)] =
              point_radiosity[static_cast<std::size_t>(leaves[f])][static_cast<std::size_t>(k)];
        }
      }
    }
  }
  summary_.peak_memory_bytes = peak_memory_bytes();
  summary_.total_seconds = total_.seconds();
  return summary_;
}

std::size_t peak_memory_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) {
      std::istringstream in(line.substr(6));
      std::size_t kb = 0;
      in >> kb;
      return kb * 1024;
    }
  }
  return 0;
}

}  // namespace hrad
