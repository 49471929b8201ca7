#include "hrad/analysis/barnes_hut.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hrad/analysis/power_law_fit.h"

namespace hrad {
namespace {

TEST(BarnesHut, ThetaZeroIsTheDirectSum) {
  const std::vector<Body> bodies = random_bodies(500, 3);
  BarnesHutOptions o;
  o.theta = 0.0;
  const BarnesHutResult r = barnes_hut(bodies, o);
  const std::vector<Vec3> direct = direct_accelerations(bodies, o.softening);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    ASSERT_EQ(r.interactions[i], bodies.size() - 1);
    EXPECT_NEAR((r.acceleration[i] - direct[i]).norm(), 0.0, 1e-12 * direct[i].norm());
  }
  EXPECT_LT(relative_rms_error(r.acceleration, direct), 1e-13);
}

TEST(BarnesHut, TwoBodiesPullEachOtherByNewtonsLaw) {
  // Masses 2 and 3 at distance 2 along x: |a_0| = 3 / (4 + eps^2)^(3/2) * 2, toward body 1.
  std::vector<Body> bodies = {{Vec3(0, 0, 0), 2.0}, {Vec3(2, 0, 0), 3.0}};
  BarnesHutOptions o;
  o.theta = 0.7;
  o.softening = 0.0;
  const BarnesHutResult r = barnes_hut(bodies, o);
  EXPECT_NEAR(r.acceleration[0].x(), 3.0 / 4.0, 1e-15);
  EXPECT_NEAR(r.acceleration[1].x(), -2.0 / 4.0, 1e-15);
}

TEST(BarnesHut, ErrorShrinksWithThetaAndStaysSmall) {
  const std::vector<Body> bodies = random_bodies(2000, 5);
  const std::vector<Vec3> direct = direct_accelerations(bodies, BarnesHutOptions{}.softening);
  double previous = 1.0;
  std::size_t previous_count = 0;
  for (double theta : {1.0, 0.7, 0.5, 0.3}) {
    BarnesHutOptions o;
    o.theta = theta;
    const BarnesHutResult r = barnes_hut(bodies, o);
    const double e = relative_rms_error(r.acceleration, direct);
    EXPECT_LT(e, previous) << theta;
    EXPECT_GT(r.mean_interactions(), previous_count) << theta;
    previous = e;
    previous_count = static_cast<std::size_t>(r.mean_interactions());
  }
  EXPECT_LT(previous, 2e-3);  // theta = 0.3, monopole only
}

TEST(BarnesHut, InteractionsPerBodyGrowLikeLogN) {
  // theta = 0.7: from n = 1000 to 8000 the naive count grows 8x; Barnes-Hut's grows like log n.
  // With bodies in the unit cube the depth of the tree (and of the walk) grows by log8(8) = 1
  // level: well below 2x, and a power-law fit over n in [1000, 16000] has a small exponent.
  std::vector<double> ns, counts;
  for (int n : {1000, 2000, 4000, 8000, 16000}) {
    BarnesHutOptions o;
    o.theta = 0.7;
    const BarnesHutResult r = barnes_hut(random_bodies(n, 11), o);
    ns.push_back(n);
    counts.push_back(r.mean_interactions());
  }
  EXPECT_LT(counts[3] / counts[0], 2.0);
  EXPECT_GT(counts[3] / counts[0], 1.0);
  const PowerLawFit fit = fit_power_law(ns, counts);
  EXPECT_LT(fit.b, 0.35);
  EXPECT_GT(fit.b, 0.0);
}

TEST(BarnesHut, SweepReportsNaiveCountsAndErrors) {
  const std::vector<BarnesHutSample> rows = barnes_hut_sweep({200, 400}, {0.0, 0.5}, 2, 300);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].naive_interactions, 199.0);
  EXPECT_EQ(rows[0].mean_interactions, 199.0);
  EXPECT_LT(rows[0].relative_force_error, 1e-13);
  EXPECT_GT(rows[1].relative_force_error, 0.0);
  EXPECT_EQ(rows[2].relative_force_error, -1.0);  // n = 400 > direct_limit
  EXPECT_EQ(rows[2].max_interactions, 399u);
}

}  // namespace
}  // namespace hrad
