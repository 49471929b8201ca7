// The sweep's gathered field (SweepRow::error_l2_gathered): each run's own final gather at the error
// samples against the reference's. In a closed convex room of uniform emission E and reflectance rho
// the exact field is B = E / (1 - rho) everywhere, and a gather of it too at every sample (the
// factors from a point to the closed surface sum to 1). A direct solve (LU: the reference and here
// the full-matrix runs) is exact to rounding, so its gathered error is 0 to 1e-9, whichever order
// the samples, reflectances and emissions are paired in; the iterative runs (substructuring, and
// hierarchical with leaf-resolved links, exact per element in a closed room) stop at the solvers'
// default tolerance, an estimated relative error of 1e-6, and a gather averages their element
// errors with weights summing to 1, times rho < 1: below 1e-5. The gather's cost is reported beside
// it, not inside the solve's seconds.
#include <cmath>

#include <gtest/gtest.h>

#include "../solvers/solver_test_scenes.h"
#include "hrad/experiments/sweep.h"

namespace hrad {
namespace {

TEST(SweepGathered, FurnaceRunsGatherTheClosedFormEverywhere) {
  const Scene box =
      test::make_box(4, 2.5, 5, {test::material(Rgb(0.8, 0.6, 0.4), Rgb(2.0, 1.0, 3.0))}, {0, 0, 0, 0, 0, 0}, true);
  SweepOptions o;
  o.element_counts = {24, 48};
  o.patch_counts = {6};
  o.feps_values = {0.1};
  o.aeps_fractions = {1e-2};
  o.samples_per_patch = 16;
  o.reference_elements = 96;
  o.full_linear_solver = LinearSolver::kLu;
  o.pushes = {Push::kLeaf};
  const Reference reference = make_reference(box, o);
  ASSERT_EQ(reference.gathered.size(), box.patches.size() * 16u);
  // The reference's gather itself: rho E / (1 - rho) per channel.
  for (const Rgb& g : reference.gathered)
    for (int c = 0; c < 3; ++c) {
      const double rho = Rgb(0.8, 0.6, 0.4)[c], e = Rgb(2.0, 1.0, 3.0)[c];
      EXPECT_NEAR(g[c], rho * e / (1 - rho), 1e-9 * e / (1 - rho));
    }
  const std::vector<SweepRow> rows = run_sweep(box, reference, o);
  // Full and substructuring at 2 element counts and one shooting-patch size, each with both bases;
  // one feps and one aeps with the leaf push, each with both bases.
  ASSERT_EQ(rows.size(), 14u);
  for (const SweepRow& r : rows) {
    const double bound = r.method == "full" ? 1e-9 : 1e-5;
    EXPECT_LT(r.error_l2_gathered, bound) << r.method << " " << r.parameter << " " << r.value;
    EXPECT_LT(r.error_linf_gathered, bound) << r.method << " " << r.parameter << " " << r.value;
    EXPECT_GT(r.gather_work, 0u);
    EXPECT_GT(r.gather_seconds, 0.0);
  }
  // Not measured when asked not to: nan, and the fits leave the field out.
  o.gather_runs = false;
  const std::vector<SweepRow> plain = run_sweep(box, reference, o);
  for (const SweepRow& r : plain) EXPECT_TRUE(std::isnan(r.error_l2_gathered));
  EXPECT_EQ(sweep_fits(plain)["methods"]["full"]["time_to_target_error_gathered"]["note"], "not measured");
  // Measured: every full run is at 0 error, so it reaches the target.
  EXPECT_TRUE(sweep_fits(rows)["methods"]["full"]["time_to_target_error_gathered"]["reached"].get<bool>());
}

}  // namespace
}  // namespace hrad
