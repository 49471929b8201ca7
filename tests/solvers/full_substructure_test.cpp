// Full-matrix and substructuring solvers against closed forms and invariants: closed rooms
// (B = E / (1 - rho) everywhere), the faceted sphere (area mean Ebar / (1 - rho)), energy balance,
// stability near rho = 1, scale invariance, the linear solvers against each other, and the Cornell
// box's convergence against the independent Monte Carlo ruler.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "hrad/core/error.h"
#include "hrad/io/obj_reader.h"
#include "hrad/reference/reference.h"
#include "hrad/solvers/full_matrix.h"
#include "hrad/solvers/solve.h"
#include "hrad/solvers/substructuring.h"
#include "solver_test_scenes.h"
#include "support/ruler_error.h"
#include "support/source_tree.h"

namespace hrad {
namespace {

using test::make_box;
using test::material;

Scene uniform_box(double rho, double e, bool t_junctions) {
  return make_box(1.0, 0.8, 1.3, {material(Rgb::Constant(rho), Rgb::Constant(e))}, {0, 0, 0, 0, 0, 0}, t_junctions);
}

double max_relative_error(const Solution& sol, const Rgb& expected) {
  double worst = 0.0;
  for (const Rgb& b : sol.face_radiosity) worst = std::max(worst, ((b - expected).abs() / expected).maxCoeff());
  return worst;
}

SolveOptions options(Method m, FormFactorKernel k = FormFactorKernel::kPointContour) {
  SolveOptions o;
  o.method = m;
  o.kernel = k;
  o.max_area = 0.1;
  o.tolerance = 1e-14;
  o.max_iterations = 200000;
  return o;
}

// --- Closed rooms --------------------------------------------------------------------------------

struct ClosedRoomCase {
  Method method;
  LinearSolver linear;
  FormFactorKernel kernel;
  double rho;
  bool t_junctions;
};

class ClosedRoom : public ::testing::TestWithParam<ClosedRoomCase> {};

TEST_P(ClosedRoom, UniformEmissionGivesEOverOneMinusRho) {
  const ClosedRoomCase c = GetParam();
  const Scene s = uniform_box(c.rho, 2.0, c.t_junctions);
  SolveOptions o = options(c.method, c.kernel);
  o.linear_solver = c.linear;
  Solution sol;
  const SolveSummary sum = solve(s, o, &sol);
  ASSERT_NE(sum.termination, Termination::kFailed) << sum.message;
  ASSERT_NE(sum.termination, Termination::kMaxIterations) << sum.message;
  if (!c.t_junctions) EXPECT_FALSE(sum.effects.visibility) << "an empty box needs no visibility";
  EXPECT_EQ(sum.effects.color_channels, 1);
  EXPECT_LT(max_relative_error(sol, Rgb::Constant(2.0 / (1.0 - c.rho))), 1e-8);
  for (const Rgb& b : sol.vertex_radiosity) EXPECT_NEAR(b[0] / (2.0 / (1.0 - c.rho)), 1.0, 1e-8);
}

INSTANTIATE_TEST_SUITE_P(
    Solvers, ClosedRoom,
    ::testing::Values(
        ClosedRoomCase{Method::kFull, LinearSolver::kLu, FormFactorKernel::kPointContour, 0.5, false},
        ClosedRoomCase{Method::kFull, LinearSolver::kLu, FormFactorKernel::kPointContour, 0.99, false},
        ClosedRoomCase{Method::kFull, LinearSolver::kLu, FormFactorKernel::kPointContour, 0.99, true},
        ClosedRoomCase{Method::kFull, LinearSolver::kLu, FormFactorKernel::kAnalytic, 0.99, true},
        ClosedRoomCase{Method::kFull, LinearSolver::kGaussSeidel, FormFactorKernel::kPointContour, 0.9, true},
        ClosedRoomCase{Method::kFull, LinearSolver::kJacobi, FormFactorKernel::kPointContour, 0.9, false},
        ClosedRoomCase{Method::kSubstructure, LinearSolver::kLu, FormFactorKernel::kPointContour, 0.5, false},
        ClosedRoomCase{Method::kSubstructure, LinearSolver::kLu, FormFactorKernel::kPointContour, 0.99, true},
        ClosedRoomCase{Method::kSubstructure, LinearSolver::kLu, FormFactorKernel::kAnalytic, 0.99, true}));

TEST(ClosedRoom, SubstructuringWithSmallerPatches) {
  const Scene s = uniform_box(0.95, 1.0, true);
  SolveOptions o = options(Method::kSubstructure);
  o.patch_area = 0.3;
  Solution sol;
  const SolveSummary sum = solve(s, o, &sol);
  EXPECT_GT(sum.figures.at("shooting_patches"), double(s.patches.size()));
  EXPECT_EQ(sum.links, sum.elements * static_cast<std::size_t>(sum.figures.at("shooting_patches")));
  EXPECT_LT(max_relative_error(sol, Rgb::Constant(1.0 / 0.05)), 1e-8);
}

// The stopping test bounds the error of the returned answer, not the last change: with the
// contraction q per iteration the remaining error is about change q / (1 - q), ten times the change
// at rho = 0.9. At the default tolerance (1e-6, relative to the largest reflected radiosity B - E)
// every element of a uniform closed cube is within 1e-6 of E / (1 - rho) in that measure, for each
// iterative solver; stopping on the change alone left 3.8e-6.
TEST(StoppingTest, ToleranceBoundsTheErrorOfTheAnswer) {
  const double rho = 0.9, e = 1.0;
  const Scene s = make_box(1.0, 1.0, 1.0, {material(Rgb::Constant(rho), Rgb::Constant(e))}, {0, 0, 0, 0, 0, 0});
  const double exact = e / (1.0 - rho), reflected = exact - e;
  for (const auto& [method, linear] :
       {std::pair{Method::kSubstructure, LinearSolver::kLu}, std::pair{Method::kFull, LinearSolver::kJacobi},
        std::pair{Method::kFull, LinearSolver::kGaussSeidel}}) {
    SolveOptions o = options(method);
    o.tolerance = 1e-6;
    o.linear_solver = linear;
    Solution sol;
    const SolveSummary sum = solve(s, o, &sol);
    ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
    double worst = 0.0;
    for (const Rgb& b : sol.face_radiosity) worst = std::max(worst, std::abs(b[0] - exact) / reflected);
    EXPECT_LT(worst, 1e-6) << to_string(method) << " " << to_string(linear);
    // The last change alone would not have bounded it.
    EXPECT_LT(sum.change_per_iteration.back(), worst) << to_string(method) << " " << to_string(linear);
  }
}

// Inside a closed convex surface the factors from any element sum to 1; with reciprocity (exact
// for the analytic kernel) the area mean is Ebar / (1 - rho) whatever the emission's distribution.
TEST(FacetedSphere, AreaMeanIsMeanEmissionOverOneMinusRho) {
  const double rho = 0.8;
  const Scene s = test::make_faceted_sphere(1.0, 5, 8, material(Rgb::Constant(rho), Rgb::Zero()),
                                            material(Rgb::Constant(rho), Rgb::Constant(5.0)));
  double ebar = 0.0;
  for (const Patch& p : s.patches) ebar += p.area * s.material_of(p).emission[0];
  ebar /= s.total_area();
  for (const Method m : {Method::kFull, Method::kSubstructure}) {
    SolveOptions o = options(m, FormFactorKernel::kAnalytic);
    o.max_area = 0.2;
    Solution sol;
    solve(s, o, &sol);
    double mean = 0.0;
    for (std::size_t p = 0; p < s.patches.size(); ++p) mean += s.patches[p].area * sol.patch_radiosity[p][0];
    mean /= s.total_area();
    EXPECT_NEAR(mean / (ebar / (1 - rho)), 1.0, 1e-8) << to_string(m);
    // The field is not uniform (the cap emits), so this is not the trivial case.
    double lo = INFINITY, hi = 0.0;
    for (const Rgb& b : sol.face_radiosity) lo = std::min(lo, b[0]), hi = std::max(hi, b[0]);
    EXPECT_GT(hi, 1.5 * lo);
  }
}

// --- Energy balance ------------------------------------------------------------------------------

// In a closed scene all emitted power is absorbed: sum A (1 - rho) H = sum A E with the irradiance
// H = (B - E) / rho read back from the solution. Holds when rows of F sum to 1 and F is reciprocal.
double energy_imbalance(const Scene& s, const Solution& sol) {
  double emitted = 0.0, absorbed = 0.0;
  for (std::size_t f = 0; f < sol.faces.size(); ++f) {
    std::vector<Vec3> poly;
    for (int v : sol.faces[f]) poly.push_back(sol.vertices[static_cast<std::size_t>(v)]);
    const double area = polygon_area(poly);
    const Material& m = s.material_of(s.patches[static_cast<std::size_t>(sol.face_patch[f])]);
    for (int c = 0; c < 3; ++c) {
      emitted += area * m.emission[c];
      absorbed += area * (1 - m.reflectance[c]) * (sol.face_radiosity[f][c] - m.emission[c]) / m.reflectance[c];
    }
  }
  return std::abs(absorbed - emitted) / emitted;
}

Scene coloured_box(bool with_block) {
  Scene s = make_box(1.0, 1.0, 1.0,
                     {material(Rgb(0.7, 0.7, 0.7), Rgb::Zero()), material(Rgb(0.6, 0.1, 0.1), Rgb::Zero()),
                      material(Rgb(0.1, 0.6, 0.1), Rgb::Zero()), material(Rgb(0.5, 0.5, 0.5), Rgb(10, 9, 7))},
                     {0, 3, 1, 2, 0, 0});
  // A floating block (with a bottom face): the scene stays closed and nothing overlaps.
  if (with_block) test::add_block(s, 0.3, 0.6, 0.1, 0.5, 0.3, 0.7, 0);
  return s;
}

TEST(EnergyBalance, ClosedColouredRoomAnalyticKernelIsExact) {
  const Scene s = coloured_box(false);
  for (const Method m : {Method::kFull, Method::kSubstructure}) {
    Solution sol;
    const SolveSummary sum = solve(s, options(m, FormFactorKernel::kAnalytic), &sol);
    EXPECT_EQ(sum.effects.color_channels, 3);
    EXPECT_LT(energy_imbalance(s, sol), 1e-9) << to_string(m);
  }
}

TEST(EnergyBalance, ClosedColouredRoomContourKernel) {
  // The contour kernel keeps closure exactly; reciprocity only to its quadrature error.
  const Scene s = coloured_box(false);
  for (const Method m : {Method::kFull, Method::kSubstructure}) {
    Solution sol;
    solve(s, options(m), &sol);
    EXPECT_LT(energy_imbalance(s, sol), 2e-3) << to_string(m);
  }
}

TEST(EnergyBalance, ClosedRoomWithOccludingBlock) {
  // Visibility is sampled (kDefaultVisibilitySamples point pairs per partial pair), so rows sum to 1 only
  // approximately.
  const Scene s = coloured_box(true);
  for (const Method m : {Method::kFull, Method::kSubstructure}) {
    Solution sol;
    SolveOptions o = options(m);
    o.max_area = 0.1;
    const SolveSummary sum = solve(s, o, &sol);
    EXPECT_TRUE(sum.effects.visibility);
    EXPECT_GT(sum.visibility_queries, 0u);
    EXPECT_LT(energy_imbalance(s, sol), 0.03) << to_string(m);
  }
}

// --- Linear solvers, stability, scale ---------------------------------------------------------------

TEST(FullMatrix, JacobiAndGaussSeidelAgreeWithLu) {
  const Scene s = coloured_box(true);
  SolveOptions o = options(Method::kFull);
  o.max_area = 0.2;
  Solution lu, jacobi, gs;
  solve(s, o, &lu);
  o.linear_solver = LinearSolver::kJacobi;
  const SolveSummary sj = solve(s, o, &jacobi);
  o.linear_solver = LinearSolver::kGaussSeidel;
  const SolveSummary sg = solve(s, o, &gs);
  EXPECT_EQ(sj.termination, Termination::kConverged);
  EXPECT_EQ(sg.termination, Termination::kConverged);
  EXPECT_LT(sg.iterations, sj.iterations) << "Gauss-Seidel uses the newest values";
  // The recorded change decreases geometrically (spectral radius <= max rho < 1).
  EXPECT_LT(sj.change_per_iteration.back(), 1e-14);
  double largest = 0.0;
  for (const Rgb& b : lu.face_radiosity) largest = std::max(largest, b.maxCoeff());
  for (std::size_t f = 0; f < lu.face_radiosity.size(); ++f) {
    EXPECT_LT((jacobi.face_radiosity[f] - lu.face_radiosity[f]).abs().maxCoeff() / largest, 1e-10);
    EXPECT_LT((gs.face_radiosity[f] - lu.face_radiosity[f]).abs().maxCoeff() / largest, 1e-10);
  }
}

TEST(Stability, ReflectanceNearOne) {
  const Scene s = uniform_box(0.999, 1.0, true);
  Solution sol;
  SolveOptions o = options(Method::kFull);
  const SolveSummary lu = solve(s, o, &sol);
  EXPECT_EQ(lu.termination, Termination::kDirect);
  EXPECT_LT(max_relative_error(sol, Rgb::Constant(1000.0)), 1e-8);
  // Iterative methods with too few iterations report it, with finite values.
  for (const Method m : {Method::kFull, Method::kSubstructure}) {
    o = options(m);
    o.linear_solver = LinearSolver::kJacobi;
    o.tolerance = 1e-6;
    o.max_iterations = 50;
    const SolveSummary it = solve(s, o, &sol);
    EXPECT_EQ(it.termination, Termination::kMaxIterations) << to_string(m);
    EXPECT_EQ(it.iterations, 50);
    for (const Rgb& b : sol.face_radiosity) EXPECT_TRUE(b.isFinite().all());
  }
  // ... and converge with enough.
  o = options(Method::kSubstructure);
  o.tolerance = 1e-13;
  const SolveSummary sub = solve(s, o, &sol);
  EXPECT_EQ(sub.termination, Termination::kConverged);
  EXPECT_LT(max_relative_error(sol, Rgb::Constant(1000.0)), 1e-8);
}

TEST(Scale, TinyAndHugeScenesGiveTheSameRadiosity) {
  const Scene s = coloured_box(true);
  for (const Method m : {Method::kFull, Method::kSubstructure}) {
    SolveOptions o = options(m);
    o.max_area = 0.2;
    Solution ref;
    solve(s, o, &ref);
    for (const double k : {1e-6, 1e6}) {
      SolveOptions ok = o;
      ok.max_area = o.max_area * k * k;
      Solution sol;
      solve(test::scaled(s, k), ok, &sol);
      ASSERT_EQ(sol.face_radiosity.size(), ref.face_radiosity.size());
      double worst = 0.0, largest = 0.0;
      for (const Rgb& b : ref.face_radiosity) largest = std::max(largest, b.maxCoeff());
      for (std::size_t f = 0; f < sol.face_radiosity.size(); ++f)
        worst = std::max(worst, (sol.face_radiosity[f] - ref.face_radiosity[f]).abs().maxCoeff() / largest);
      EXPECT_LT(worst, 1e-6) << to_string(m) << " scale " << k;
    }
  }
}

TEST(FullMatrix, LinksAndCounters) {
  const Scene s = coloured_box(false);
  SolveOptions o = options(Method::kFull);
  o.max_area = 0.3;
  Solution sol;
  const SolveSummary sum = solve(s, o, &sol);
  EXPECT_EQ(sum.links, sum.elements * sum.elements);
  // Each unordered pair of elements on different walls that face each other is one evaluation.
  EXPECT_GT(sum.form_factor_evaluations, 0u);
  EXPECT_LE(sum.form_factor_evaluations, sum.elements * (sum.elements - 1) / 2);
  EXPECT_EQ(sol.faces.size(), sum.elements);
  EXPECT_GT(sum.total_seconds, 0.0);
}

// --- The bundled Cornell box -----------------------------------------------------------------------

// Both methods against the independent ruler (reference_faces: Monte Carlo path tracing on its own
// rays, no form factor shared), per input face: the area-weighted relative L2 of the face means of
// the reflected radiosity B - E, as `hrad compare` scores it (support/ruler_error.h). Constant elements converge at
// least as O(h), so 4x the elements (h / 2) must at least halve the full matrix's error. Substructuring receives on the
// same mesh and shoots from patches: its error is the receivers' (the full matrix's on that mesh) plus the shooters';
// the shooters' part, sqrt(e_sub^2 - e_full^2), must at least halve with 4x the patches. The ruler's own noise (its
// standard errors in the same norm) is asserted small beside every error it judges.
TEST(CornellBox, FullAndSubstructuringConvergeToTheRuler) {
  const Scene s = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  ReferenceOptions ro;
  ro.samples = 262144;  // its noise, over the three channels, a quarter of the finest run's error or less
  std::vector<FaceEstimate> ruler;
  reference_faces(s, ro, &ruler);
  auto error_of = [&](Method m, double elements, double patches) {
    SolveOptions o;
    o.method = m;
    o.max_area = s.total_area() / elements;
    o.patch_area = s.total_area() / patches;
    Solution sol;
    const SolveSummary sum = solve(s, o, &sol);
    EXPECT_TRUE(sum.termination == Termination::kDirect || sum.termination == Termination::kConverged) << sum.message;
    const FaceErrors e = test::errors_against_ruler(s, sol, ruler);
    EXPECT_LT(e.reference_noise, 0.25 * e.relative_l2) << to_string(m) << ": the ruler is too noisy to judge this";
    return e.relative_l2;
  };
  const double full_coarse = error_of(Method::kFull, 32, 32), full_fine = error_of(Method::kFull, 128, 32);
  EXPECT_LT(full_fine, 0.5 * full_coarse) << full_coarse << " -> " << full_fine;
  const double sub_coarse = error_of(Method::kSubstructure, 128, 16),
               sub_fine = error_of(Method::kSubstructure, 128, 64);
  const auto shooters = [&](double e) { return std::sqrt(std::max(0.0, e * e - full_fine * full_fine)); };
  EXPECT_LT(shooters(sub_fine), 0.5 * shooters(sub_coarse))
      << sub_coarse << " -> " << sub_fine << " (receivers " << full_fine << ")";
}

// Hierarchical radiosity against the same ruler (262,144 paths a face). Where its mesh is fine enough to
// claim the face means (aeps total/16000, or linear elements at the defaults), its error per face is
// the ruler's own noise: the relative L2 within 1.5 times the ruler's noise in the same norm, whose
// expectation it is for an exact answer. The control: at the defaults' constant elements the ruler
// resolves the solver's error (more than twice its noise), so the bound is not met by noise alone.
TEST(CornellBox, HierarchicalFaceMeansAgreeWithTheRulerWithinItsNoise) {
  const Scene s = read_obj_scene(test::source_dir() + "/notebooks_data/scenes/cornell_box.obj");
  ReferenceOptions ro;
  ro.samples = 262144;
  std::vector<FaceEstimate> ruler;
  reference_faces(s, ro, &ruler);
  const auto errors = [&](double aeps_share, Basis basis) {
    SolveOptions o;
    o.method = Method::kHierarchical;
    o.aeps = s.total_area() * aeps_share;
    o.basis = basis;
    Solution sol;
    const SolveSummary sum = solve(s, o, &sol);
    EXPECT_EQ(sum.termination, Termination::kConverged) << sum.message;
    return test::errors_against_ruler(s, sol, ruler);
  };
  const FaceErrors defaults = errors(1.0 / 1000, Basis::kConstant);
  const FaceErrors fine = errors(1.0 / 16000, Basis::kConstant);
  const FaceErrors linear = errors(1.0 / 1000, Basis::kLinear);
  std::printf(
      "relative L2 per face against the ruler (its noise %.3f%%): defaults %.3f%%, total/16000 %.3f%%, "
      "linear %.3f%%\n",
      100 * fine.reference_noise, 100 * defaults.relative_l2, 100 * fine.relative_l2, 100 * linear.relative_l2);
  EXPECT_GT(defaults.relative_l2, 2.0 * defaults.reference_noise);
  EXPECT_LT(fine.relative_l2, 1.5 * fine.reference_noise);
  EXPECT_LT(linear.relative_l2, 1.5 * linear.reference_noise);
}

// --- Options ----------------------------------------------------------------------------------------

TEST(Options, OutOfRangeValuesNameTheOption) {
  const Scene s = uniform_box(0.5, 1.0, false);
  auto message = [&](SolveOptions o) {
    try {
      solve(s, o, nullptr);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SolveOptions o;
  o.feps = -1;
  EXPECT_EQ(message(o), "--feps must be >= 0 (0 = unused), got -1");
  o = {};
  o.tolerance = 0;
  EXPECT_EQ(message(o), "--tolerance must be > 0, got 0");
  o = {};
  o.tolerance = NAN;
  EXPECT_NE(message(o).find("--tolerance"), std::string::npos);
  o = {};
  o.max_area = -3;
  EXPECT_NE(message(o).find("--max-area must be >= 0"), std::string::npos);
  o = {};
  o.aeps = INFINITY;
  EXPECT_NE(message(o).find("--aeps"), std::string::npos);
  o = {};
  o.max_iterations = 0;
  EXPECT_NE(message(o).find("--max-iterations"), std::string::npos);
  o = {};
  o.method = static_cast<Method>(7);
  EXPECT_NE(message(o).find("--method"), std::string::npos);
  EXPECT_THROW(parse_method("fast"), Error);
  EXPECT_EQ(parse_method("substructure"), Method::kSubstructure);
  EXPECT_EQ(parse_linear_solver("gauss-seidel"), LinearSolver::kGaussSeidel);
  EXPECT_THROW(parse_effects_mode("some"), Error);
}

}  // namespace
}  // namespace hrad
