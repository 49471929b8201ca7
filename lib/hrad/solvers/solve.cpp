#include "hrad/solvers/solve.h"

#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/core/memory.h"
#include "hrad/solvers/full_matrix.h"
#include "hrad/solvers/hierarchical.h"
#include "hrad/solvers/substructuring.h"
#include "hrad/solvers/work_estimate.h"

namespace hrad {
namespace {

// Options where 0 means "automatic" or "unused": finite and >= 0.
void check_non_negative(const char* option, double value, const char* zero_means) {
  if (!std::isfinite(value) || value < 0.0)
    throw Error(fmt::format("{} must be >= 0 (0 = {}), got {}", option, zero_means, value));
}

void check_positive(const char* option, double value) {
  if (!std::isfinite(value) || value <= 0.0) throw Error(fmt::format("{} must be > 0, got {}", option, value));
}

}  // namespace

SourceLevels parse_source_levels(const std::string& text) {
  if (text == "auto") return {kAutoSourceLevels, true};
  int n = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || end != text.data() + text.size() || n < 0 || n > kMaxSourceLevels)
    throw Error(fmt::format("--source-levels must be auto or an integer in [0, {}], got '{}'", kMaxSourceLevels, text));
  return {n, false};
}

void validate_options(const SolveOptions& o) {
  switch (o.method) {
    case Method::kFull:
    case Method::kSubstructure:
    case Method::kHierarchical:
      break;
    default:
      throw Error(fmt::format("--method: unknown method {}", static_cast<int>(o.method)));
  }
  check_non_negative("--max-area", o.max_area, "automatic");
  check_non_negative("--patch-area", o.patch_area, "the input polygons");
  check_non_negative("--feps", o.feps, "unused");
  check_non_negative("--bfeps", o.bfeps, "unused");
  check_non_negative("--aeps", o.aeps, "automatic");
  if (o.source_levels < 0 || o.source_levels > kMaxSourceLevels)
    throw Error(fmt::format("--source-levels must be in [0, {}], got {}", kMaxSourceLevels, o.source_levels));
  check_positive("--tolerance", o.tolerance);
  if (!(o.power_noise == 0.0 || (o.power_noise >= kLeastPowerNoise && o.power_noise <= 1.0)))
    throw Error(fmt::format("--power-noise must be 0 (default sampling) or in [{}, 1], got {}", kLeastPowerNoise,
                            o.power_noise));
  if (o.max_iterations < 1) throw Error(fmt::format("--max-iterations must be >= 1, got {}", o.max_iterations));
  switch (o.linear_solver) {
    case LinearSolver::kLu:
    case LinearSolver::kJacobi:
    case LinearSolver::kGaussSeidel:
      break;
    default:
      throw Error(fmt::format("--linear-solver: unknown solver {}", static_cast<int>(o.linear_solver)));
  }
  if (o.effects != EffectsMode::kAuto && o.effects != EffectsMode::kAll)
    throw Error(fmt::format("--effects: unknown mode {}", static_cast<int>(o.effects)));
  if (o.kernel != FormFactorKernel::kAnalytic && o.kernel != FormFactorKernel::kPointContour)
    throw Error(fmt::format("--kernel: unknown kernel {}", static_cast<int>(o.kernel)));
  if (o.visibility_samples < 1 || o.visibility_samples > kMaxVisibilitySamples)
    throw Error(
        fmt::format("--visibility-samples must be in [1, {}], got {}", kMaxVisibilitySamples, o.visibility_samples));
  if (o.clustering != Clustering::kAuto && o.clustering != Clustering::kOn && o.clustering != Clustering::kOff)
    throw Error(fmt::format("--clustering: unknown mode {}", static_cast<int>(o.clustering)));
  if (o.push != Push::kHsa && o.push != Push::kLeaf)
    throw Error(fmt::format("--push: unknown operator {}", static_cast<int>(o.push)));
  if (o.basis != Basis::kConstant && o.basis != Basis::kLinear)
    throw Error(fmt::format("--basis: unknown basis {}", static_cast<int>(o.basis)));
  if (o.basis == Basis::kLinear && o.method == Method::kFull && o.linear_solver != LinearSolver::kJacobi)
    throw Error(
        fmt::format("--basis linear with --method full iterates the corner values by Jacobi (--linear-solver "
                    "jacobi), not {}",
                    to_string(o.linear_solver)));
  if (o.threads < 0) throw Error(fmt::format("--threads must be >= 0 (0 = all cores), got {}", o.threads));
}

SolveSummary solve(const Scene& scene, const SolveOptions& options, Solution* out, SolvedHierarchy* kept) {
  validate_options(options);
  // Before any meshing: refuse what cannot fit or would take days, naming the option to change.
  check_work(estimate_work(scene, options), to_string(options.method), available_memory_bytes());
  // Each phase names what it allocates (SolverContext::Phase); this covers the rest of the solve.
  const AllocationScope allocating(fmt::format("the {} solve", to_string(options.method)),
                                   smaller_work(options.method));
  switch (options.method) {
    case Method::kFull:
      return solve_full_matrix(scene, options, out);
    case Method::kSubstructure:
      return solve_substructuring(scene, options, out);
    case Method::kHierarchical:
      return solve_hierarchical(scene, options, out, kept);
  }
  throw Error("--method: unknown method");
}

std::string_view to_string(Method method) {
  switch (method) {
    case Method::kFull:
      return "full";
    case Method::kSubstructure:
      return "substructure";
    case Method::kHierarchical:
      return "hierarchical";
  }
  return "unknown";
}

std::string_view to_string(Termination termination) {
  switch (termination) {
    case Termination::kConverged:
      return "converged";
    case Termination::kMaxIterations:
      return "max_iterations";
    case Termination::kDirect:
      return "direct";
    case Termination::kFailed:
      return "failed";
  }
  return "unknown";
}

std::string_view to_string(LinearSolver solver) {
  switch (solver) {
    case LinearSolver::kLu:
      return "lu";
    case LinearSolver::kJacobi:
      return "jacobi";
    case LinearSolver::kGaussSeidel:
      return "gauss_seidel";
  }
  return "unknown";
}

std::string_view to_string(EffectsMode mode) {
  switch (mode) {
    case EffectsMode::kAuto:
      return "auto";
    case EffectsMode::kAll:
      return "all";
  }
  return "unknown";
}

Method parse_method(std::string_view text) {
  if (text == "full") return Method::kFull;
  if (text == "substructure" || text == "substructuring") return Method::kSubstructure;
  if (text == "hierarchical") return Method::kHierarchical;
  throw Error(fmt::format("--method must be full, substructure or hierarchical, got '{}'", text));
}

LinearSolver parse_linear_solver(std::string_view text) {
  if (text == "lu") return LinearSolver::kLu;
  if (text == "jacobi") return LinearSolver::kJacobi;
  if (text == "gauss_seidel" || text == "gauss-seidel") return LinearSolver::kGaussSeidel;
  throw Error(fmt::format("--linear-solver must be lu, jacobi or gauss_seidel, got '{}'", text));
}

std::string_view to_string(FormFactorKernel kernel) {
  switch (kernel) {
    case FormFactorKernel::kAnalytic:
      return "analytic";
    case FormFactorKernel::kPointContour:
      return "contour";
  }
  return "unknown";
}

FormFactorKernel parse_kernel(std::string_view text) {
  if (text == "analytic") return FormFactorKernel::kAnalytic;
  if (text == "contour") return FormFactorKernel::kPointContour;
  throw Error(fmt::format("--kernel must be analytic or contour, got '{}'", text));
}

std::string_view to_string(Clustering clustering) {
  switch (clustering) {
    case Clustering::kAuto:
      return "auto";
    case Clustering::kOn:
      return "on";
    case Clustering::kOff:
      return "off";
  }
  return "unknown";
}

Clustering parse_clustering(std::string_view text) {
  if (text == "auto") return Clustering::kAuto;
  if (text == "on") return Clustering::kOn;
  if (text == "off") return Clustering::kOff;
  throw Error(fmt::format("--clustering must be auto, on or off, got '{}'", text));
}

std::string_view to_string(Push push) {
  switch (push) {
    case Push::kHsa:
      return "hsa";
    case Push::kLeaf:
      return "leaf";
  }
  return "unknown";
}

Push parse_push(std::string_view text) {
  if (text == "hsa") return Push::kHsa;
  if (text == "leaf") return Push::kLeaf;
  throw Error(fmt::format("--push must be hsa or leaf, got '{}'", text));
}

std::string_view to_string(Basis basis) {
  switch (basis) {
    case Basis::kConstant:
      return "constant";
    case Basis::kLinear:
      return "linear";
  }
  return "unknown";
}

Basis parse_basis(std::string_view text) {
  if (text == "constant") return Basis::kConstant;
  if (text == "linear") return Basis::kLinear;
  throw Error(fmt::format("--basis must be constant or linear, got '{}'", text));
}

EffectsMode parse_effects_mode(std::string_view text) {
  if (text == "auto") return EffectsMode::kAuto;
  if (text == "all") return EffectsMode::kAll;
  throw Error(fmt::format("--effects must be auto or all, got '{}'", text));
}

}  // namespace hrad
