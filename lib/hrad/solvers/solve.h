// The solvers' shared entry point: options, summary and solve(). Failures to converge are a
// Termination in the summary, not an exception; invalid options are an hrad::Error before any work.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/solvers/effects.h"
#include "hrad/solvers/form_factor_evaluator.h"
#include "hrad/solvers/work.h"

namespace hrad {

enum class Method {
  kFull,          ///< classical radiosity: n elements, the n x n form-factor matrix, Eigen
  kSubstructure,  ///< Cohen et al. 1986: patches shoot, elements receive (n x N factors)
  kHierarchical,  ///< Hanrahan, Salzman & Aupperle 1991: quadtrees, links, push-pull
};

/// How the full-matrix system (I - rho F) B = E is solved.
enum class LinearSolver {
  kLu,           ///< Eigen's partial-pivoting LU: the direct reference
  kJacobi,       ///< B <- E + rho F B, all elements from the previous iterate
  kGaussSeidel,  ///< the same, each element using the newest values
};

/// Hierarchical radiosity above the input polygons (Smits, Arvo & Greenberg 1994).
enum class Clustering {
  kAuto,  ///< on when the scene has at least kAutoClusteringPatches patches
  kOn,    ///< a cluster hierarchy over the patches, linked from one root self-link
  kOff,   ///< plain HSA: every pair of input patches is an initial link (k^2)
};

/// How a hierarchical solve gathers over its links (hierarchical.h).
enum class Push {
  kHsa,   ///< HSA 1991: gather at the linked nodes, push down, pull up; O(links + nodes) per iteration
  kLeaf,  ///< each element link resolved to the leaves on both sides with their own factors
};

/// The radiosity over each leaf element (linear_basis.h).
enum class Basis {
  kConstant,  ///< one value per element (the classical element)
  /// Linear on a triangle, bilinear on a quad's map: the L2 projection of E + rho H (hierarchical
  /// with Push::kHsa; full matrix with LinearSolver::kJacobi; substructuring).
  kLinear,
};

/// Clustering::kAuto turns clustering on from this many patches (below it the k^2 initial pairs
/// are cheap and plain HSA is the reference).
inline constexpr std::size_t kAutoClusteringPatches = 200;

/// Default point pairs per partly visible pair. A coarse link's visible fraction is one number for a
/// whole penumbra, so its sampling noise does not average out as elements shrink: the count must be
/// large enough that the noise stays below the discretisation error of fine meshes (on the Cornell
/// box, 16 were not and 256 gave the same answer as 64; `hrad sweep --visibility-samples K` measures it).
inline constexpr int kDefaultVisibilitySamples = 64;

/// The most quadtree levels below aeps that --source-levels allows (aeps / 4096).
inline constexpr int kMaxSourceLevels = 6;
/// `--source-levels auto`: this many levels, near bright emitters only (SolveOptions).
inline constexpr int kAutoSourceLevels = 2;

/// `--source-levels` as given: `auto`, or an integer in [0, kMaxSourceLevels].
struct SourceLevels {
  int levels = 0;
  bool near_lamps = false;
};
/// Reads `--source-levels TEXT`; anything else is an Error naming the option.
SourceLevels parse_source_levels(const std::string& text);

/// The smallest SolveOptions::power_noise accepted: below it the rays it asks for pass what a solve
/// can afford (25x the cluster links' rays at 1e-4).
inline constexpr double kLeastPowerNoise = 1e-4;

struct SolveOptions {
  Method method = Method::kHierarchical;
  /// Full matrix and substructuring: largest element area (scene units squared); 0 = automatic:
  /// total area / kAutoElements (uniform 1-to-4 splits then give 1 to 4 times that many elements).
  double max_area = 0.0;
  /// Substructuring: largest shooting-patch area; 0 = automatic (kAutoPatchAreaFraction of the total area).
  double patch_area = 0.0;
  /// Hierarchical: form-factor refinement tolerance (HSA 1991 Fε); 0 = unused.
  double feps = 0.0;
  /// Hierarchical: B*F refinement tolerance (HSA 1991 BFε, radiosity units); 0 = unused.
  double bfeps = 0.0;
  /// Hierarchical: smallest element area (HSA 1991 Aε, scene units squared); 0 = automatic.
  double aeps = 0.0;
  /// Hierarchical, HSA push: quadtree levels below aeps to which a source element may still split
  /// where a receiver's kernel peaks over part of it (contacts, lamp housings;
  /// OracleTolerances::source_levels); 0 = aeps bounds every split.
  int source_levels = 0;
  /// With source_levels: only elements of patches near a bright emitter (within its diameter,
  /// core/bright_emitters.h) split below aeps, where a lamp's light varies most (its housing, the
  /// walls beside it); elsewhere aeps bounds every split. `--source-levels auto`: kAutoSourceLevels so.
  bool source_levels_near_lamps = false;
  /// Iterations stop when the estimated error of the returned radiosity is below this, relative in
  /// two measures (stopping_change(), iteration.h): the largest leaf's against the largest reflected
  /// radiosity B - E, and the reflected power's (the change integrated over the leaves' areas)
  /// against the reflected power. The error is the last change times q / (1 - q), q the contraction
  /// per iteration estimated from successive changes (a geometric tail; see
  /// SolverContext::record_iteration()). Relative to B - E rather than B: a bright emitter would
  /// otherwise stop the iteration before any interreflection.
  double tolerance = 1e-6;
  /// Iterative methods give up (Termination::kMaxIterations) after this many iterations.
  int max_iterations = 10000;
  LinearSolver linear_solver = LinearSolver::kLu;
  EffectsMode effects = EffectsMode::kAuto;
  /// The unoccluded form-factor kernel of every solver (see FormFactorKernel).
  FormFactorKernel kernel = FormFactorKernel::kPointContour;
  /// Point pairs sampled per partially visible pair (the visibility oracle's `samples`).
  int visibility_samples = kDefaultVisibilitySamples;
  /// The sample stream: every sampled quantity (visible fractions, cluster factors) draws from
  /// seeds of the pair's geometry mixed with this, so 0 gives the default solution bit for bit and
  /// other values give independent draws of the same estimators: the spread of a result over a few
  /// seeds is its sampling noise.
  std::uint64_t seed = 0;
  /// Hierarchical: the standard deviation over sample streams that the power balance (absorbed over
  /// emitted) should have, or 0 for the default sampling (OracleTolerances::power_noise).
  double power_noise = 0.0;
  /// Hierarchical with the HSA push: when the solve's light is found to stay in the scene
  /// (closed_scene.h), every leaf's sends are closed to 1, so that the power balances by
  /// construction; off: the links' sampled closure stands (--closure off).
  bool close_closed_scenes = true;
  /// Gather the irradiance even where nothing reflects (every reflectance 0), so that
  /// Solution::face_irradiance holds H for radiant exchange (black surfaces still absorb).
  bool irradiance = false;
  /// Hierarchical: also return each link pair as a segment between element centroids
  /// (Solution::link_segments), for figures.
  bool record_links = false;
  /// Hierarchical: clustering above the input polygons (see Clustering).
  Clustering clustering = Clustering::kAuto;
  /// Hierarchical: the link operator (see Push).
  Push push = Push::kHsa;
  /// Balance the leaves after meshing or refinement (ElementHierarchy::balance(): at most one level
  /// between edge neighbours), so the output mesh has no long T-edges.
  bool balance = false;
  /// The radiosity basis on the leaves (see Basis).
  Basis basis = Basis::kConstant;
  /// Worker threads for the parallel phases; 0 = TBB's default (all cores).
  int threads = 0;
  /// Called with one line of progress for long phases (the CLI prints it on stderr); may be empty.
  std::function<void(std::string_view)> progress;
  /// Seconds between two progress lines of one phase (and from its start to its first line): short
  /// work prints nothing. 0 prints a line at every step (for tests).
  double progress_interval_seconds = 2.0;
};

/// Automatic max_area = total area / kAutoElements (full matrix and substructuring): 492 elements
/// on the bundled Cornell box, a few seconds for the full matrix with visibility.
inline constexpr double kAutoElements = 250.0;

enum class Termination {
  kConverged,      ///< an iterative method met the tolerance
  kMaxIterations,  ///< an iterative method ran out of iterations (the answer is the last iterate)
  kDirect,         ///< a direct solve (LU, or B = E when nothing reflects)
  kFailed,         ///< a numerical failure (non-finite values, singular system); see message
};

struct SolveSummary {
  Method method = Method::kHierarchical;
  Termination termination = Termination::kFailed;
  std::string message;  ///< one line for people: how it ended and why
  int iterations = 0;
  std::size_t patches = 0;   ///< input patches (Scene::patches)
  std::size_t elements = 0;  ///< leaves of the element hierarchy
  std::size_t links = 0;     ///< interactions: n^2 (full), n*N (substructuring), links (hierarchical)
  std::uint64_t form_factor_evaluations = 0;
  std::uint64_t visibility_queries = 0;
  /// What the solve did, counted where it was done (work.h).
  Work work;
  /// The options as the solve used them: automatic values (max_area, patch_area, feps, aeps)
  /// filled in, the kernel the method used.
  SolveOptions used;
  /// Wall-clock seconds per phase ("setup", "effects", "mesh", "form_factors", "solve",
  /// "refine", "output", ...) in the order they ran, and the whole solve.
  std::vector<std::pair<std::string, double>> seconds;
  double total_seconds = 0.0;
  Effects effects;  ///< what was simulated and why
  /// The stopping measure per iteration (stopping_change(); SolveOptions::tolerance), for plots.
  std::vector<double> change_per_iteration;
  std::size_t peak_memory_bytes = 0;  ///< the process's peak resident set (0 if unknown)
  /// Method-specific figures for the report (e.g. "max_area", "patch_area", "shooting_patches").
  std::map<std::string, double> figures;
};

/// Checks every option before any work; throws hrad::Error naming the option as the command line
/// spells it ("--feps must be >= 0, got -1"). NaN and infinities are rejected everywhere.
void validate_options(const SolveOptions& options);

struct SolvedHierarchy;

/// Solves `scene` with options.method and writes the leaf mesh to `out` (if not null).
/// Validates the options first. A hierarchical solve also hands its hierarchy and links to `kept`
/// when given (solved_hierarchy.h); other methods leave it empty.
SolveSummary solve(const Scene& scene, const SolveOptions& options, Solution* out, SolvedHierarchy* kept = nullptr);

std::string_view to_string(Method method);
std::string_view to_string(Termination termination);
std::string_view to_string(LinearSolver solver);
std::string_view to_string(EffectsMode mode);
std::string_view to_string(FormFactorKernel kernel);
std::string_view to_string(Clustering clustering);
std::string_view to_string(Push push);
std::string_view to_string(Basis basis);
/// Parses "constant" | "linear"; throws hrad::Error naming --basis otherwise.
Basis parse_basis(std::string_view text);
/// Parses "hsa" | "leaf"; throws hrad::Error naming --push otherwise.
Push parse_push(std::string_view text);
/// Parses "auto" | "on" | "off"; throws hrad::Error naming --clustering otherwise.
Clustering parse_clustering(std::string_view text);
/// Parses "analytic" | "contour"; throws hrad::Error naming --kernel otherwise.
FormFactorKernel parse_kernel(std::string_view text);
/// Parses "full" | "substructure" | "hierarchical"; throws hrad::Error naming --method otherwise.
Method parse_method(std::string_view text);
/// Parses "lu" | "jacobi" | "gauss_seidel" (or "gauss-seidel"); throws hrad::Error naming --linear-solver.
LinearSolver parse_linear_solver(std::string_view text);
/// Parses "auto" | "all"; throws hrad::Error naming --effects.
EffectsMode parse_effects_mode(std::string_view text);

}  // namespace hrad
