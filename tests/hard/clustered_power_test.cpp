// Power conservation of clustered hierarchical radiosity (Smits, Arvo & Greenberg 1994) at the
// defaults, on closed scenes with exact answers. In a closed scene of one reflectance rho every
// patch's factors sum to 1, so the area-mean radiosity is Ebar / (1 - rho) exactly and the power
// absorbed equals the power emitted. A cluster link's factor is a sampled estimate; what it may err
// is random and of either sign, so the sums over many links must still balance.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "../solvers/solver_test_scenes.h"
#include "hrad/analysis/error_metrics.h"
#include "hrad/solvers/solve.h"

namespace hrad {
namespace {

Material grey(double rho, double e) { return {"m", Rgb::Constant(rho), Rgb::Constant(e)}; }

double area_mean(const Scene& s, const Solution& sol) {
  double sum = 0.0;
  for (std::size_t i = 0; i < s.patches.size(); ++i) sum += s.patches[i].area * sol.patch_radiosity[i][0];
  return sum / s.total_area();
}

SolveOptions defaults() {
  SolveOptions o;
  o.method = Method::kHierarchical;
  return o;
}

// A closed sphere of reflectance `rho` solved at the defaults with clustering: absorbed / emitted
// within 1e-3 of 1 (either side), and the area-mean radiosity within 1e-3 of Ebar / (1 - rho).
void expect_sphere_keeps_power(const Scene& s, double rho) {
  SCOPED_TRACE(::testing::Message() << s.patches.size() << " patches");
  double emitted = 0.0;
  for (const Patch& p : s.patches) emitted += p.area * s.material_of(p).emission[0];
  Solution sol;
  const SolveSummary sum = solve(s, defaults(), &sol);
  ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
  EXPECT_GT(sum.figures.at("cluster_link_pairs"), 0.0);
  EXPECT_LT(std::abs(energy_balance(s, sol).closed_scene_residual[0]), 1e-3);
  EXPECT_NEAR(area_mean(s, sol) * (1 - rho) / (emitted / s.total_area()), 1.0, 1e-3);
}

// Guarantee: a closed faceted sphere whose polar cap emits keeps its power at the defaults
// (clustering on: more than 200 patches): absorbed / emitted within 1e-3 of 1, and the area-mean
// radiosity within 1e-3 of Ebar / (1 - rho).
TEST(ClusteredPower, ClosedSphereWithAnEmittingCapBalancesPower) {
  const double rho = 0.6;
  for (const int sectors : {16, 28}) {
    const Scene s = test::make_faceted_sphere(1.5, 14, sectors, grey(rho, 0.0), grey(rho, 5.0));
    ASSERT_GT(s.patches.size(), kAutoClusteringPatches);
    expect_sphere_keeps_power(s, rho);
  }
}

// The sphere turned by `angle` about an oblique axis: no facet is axis-aligned any more, so every
// cluster's projected areas must be taken per patch (per-axis sums would misplace the power).
Scene tilted(Scene s, double angle) {
  const Eigen::Matrix3d m = Eigen::AngleAxisd(angle, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (Patch& p : s.patches) {
    for (Vec3& v : p.vertices) v = m * v;
    p.normal = m * p.normal;
  }
  return s;
}

// Guarantee: the same holds for tilted spheres of other facetings: absorbed / emitted within 1e-3
// of 1, and the area-mean radiosity within 1e-3 of Ebar / (1 - rho).
TEST(ClusteredPower, TiltedSpheresBalancePower) {
  const double rho = 0.5;
  for (const auto& [rings, sectors, angle] : {std::tuple{12, 24, 0.45}, std::tuple{18, 20, 1.1}}) {
    const Scene s = tilted(test::make_faceted_sphere(2.0, rings, sectors, grey(rho, 0.0), grey(rho, 3.0)), angle);
    expect_sphere_keeps_power(s, rho);
  }
}

// Guarantee: a uniformly emitting closed room of many patches (a tilted faceted sphere, every
// facet emitting) is uniform clustered: every patch within 1% of E / (1 - rho).
TEST(ClusteredPower, UniformClosedRoomIsUniformPerPatch) {
  const double rho = 0.7;
  const Scene s = tilted(test::make_faceted_sphere(1.0, 14, 30, grey(rho, 1.0), grey(rho, 1.0)), 0.8);
  Solution sol;
  const SolveSummary sum = solve(s, defaults(), &sol);
  ASSERT_EQ(sum.termination, Termination::kConverged) << sum.message;
  EXPECT_GT(sum.figures.at("cluster_link_pairs"), 0.0);
  for (std::size_t i = 0; i < s.patches.size(); ++i) EXPECT_NEAR(sol.patch_radiosity[i][0] * (1 - rho), 1.0, 0.01) << i;
}

// Control: the same sphere with one shell facet removed is open, and the test above would see the
// loss. In a sphere every point receives the same irradiance H from any part of the shell (F =
// A_j / A), so the hole lets out A_h H while the shell absorbs (1 - rho) (A - A_h) H: the share lost
// is a / (a + (1 - rho) (1 - a)) with a = A_h / A (about 1.1% here); the faceting perturbs H by
// about a percent, far less than the 10% allowed.
TEST(ClusteredPower, ASphereWithAHoleLosesWhatLeavesThroughIt) {
  const double rho = 0.6;
  Scene s = test::make_faceted_sphere(1.5, 14, 16, grey(rho, 0.0), grey(rho, 5.0));
  const double total = s.total_area();
  const std::size_t hole = s.patches.size() / 2;  // a facet on the equator
  const double a = s.patches[hole].area / total;
  s.patches.erase(s.patches.begin() + static_cast<std::ptrdiff_t>(hole));
  s.faces.erase(s.faces.begin() + static_cast<std::ptrdiff_t>(hole));
  for (std::size_t i = hole; i < s.patches.size(); ++i) {
    s.patches[i].face = static_cast<int>(i);
    s.faces[i].patches = {static_cast<int>(i)};
  }
  Solution sol;
  solve(s, defaults(), &sol);
  const double lost = a / (a + (1 - rho) * (1 - a));
  EXPECT_NEAR(energy_balance(s, sol).closed_scene_residual[0], lost, 0.1 * lost);
}

}  // namespace
}  // namespace hrad
