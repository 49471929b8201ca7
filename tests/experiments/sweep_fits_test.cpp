// sweep_fits() on synthetic sweeps with known laws: the exponents come back, and the time-to-error
// ratios are what the laws give (time and error are both powers of n, so the log-log interpolation
// between runs is exact).
#include <gtest/gtest.h>

#include <cmath>

#include "hrad/experiments/sweep.h"

namespace hrad {
namespace {

// Full: time 1e-5 n^2, links n^2; hierarchical: time 1e-3 n, links 20 n; both error 2 / sqrt(n)
// (the displayed field: 1 / sqrt(n)).
std::vector<SweepRow> synthetic_sweep() {
  std::vector<SweepRow> rows;
  for (const double n : {100.0, 200.0, 400.0, 800.0, 1600.0, 3200.0})
    for (const bool hr : {false, true}) {
      SweepRow r;
      r.method = hr ? "hierarchical" : "full";
      r.parameter = hr ? "aeps" : "max_area";
      r.value = 1.0 / n;
      r.elements = static_cast<std::size_t>(n);
      r.links = static_cast<std::size_t>(hr ? 20 * n : n * n);
      r.seconds = hr ? 1e-3 * n : 1e-5 * n * n;
      r.error_l2 = 2.0 / std::sqrt(n);
      r.error_l2_smooth = 1.0 / std::sqrt(n);
      rows.push_back(r);
    }
  return rows;
}

TEST(SweepFits, RecoverTheExponentsOfSyntheticLaws) {
  const nlohmann::json j = sweep_fits(synthetic_sweep());
  EXPECT_NEAR(j["methods"]["full"]["time_vs_elements"]["b"].get<double>(), 2.0, 1e-6);
  EXPECT_NEAR(j["methods"]["full"]["links_vs_elements"]["b"].get<double>(), 2.0, 1e-6);
  EXPECT_NEAR(j["methods"]["hierarchical"]["time_vs_elements"]["b"].get<double>(), 1.0, 1e-6);
  EXPECT_NEAR(j["methods"]["hierarchical"]["links_vs_elements"]["a"].get<double>(), 20.0, 1e-4);
}

TEST(SweepFits, TimeToATargetErrorIsInterpolatedBetweenRuns) {
  // Target 0.06 lies between n = 800 and 1600 for the constant field: n* = (2 / 0.06)^2, where the
  // full matrix takes 1e-5 n*^2 and HR 1e-3 n*: their ratio is 1e-2 n* = 11.11.
  const nlohmann::json j = sweep_fits(synthetic_sweep(), 0.06);
  const double n = std::pow(2.0 / 0.06, 2.0);
  const auto& full = j["methods"]["full"]["time_to_target_error"];
  ASSERT_TRUE(full["reached"].get<bool>());
  EXPECT_NEAR(full["interpolated_seconds"].get<double>(), 1e-5 * n * n, 1e-9 * n * n);
  EXPECT_DOUBLE_EQ(full["measured_seconds"].get<double>(), 1e-5 * 1600.0 * 1600.0);
  EXPECT_NEAR(j["speedup"]["full_over_hierarchical_interpolated"].get<double>(), 1e-2 * n, 1e-9 * n);
  // The displayed field reaches 0.06 at n = (1 / 0.06)^2 = 278.
  EXPECT_NEAR(j["speedup_smooth"]["full_over_hierarchical_interpolated"].get<double>(),
              1e-2 * std::pow(1.0 / 0.06, 2.0), 1e-9 * n);
  EXPECT_FALSE(j.contains("speedup_at_common_error"));
}

TEST(SweepFits, BelowEveryRunTheRatioIsStatedAtTheLowestCommonError) {
  // Target 1%: no run reaches it (the finest has 2 / sqrt(3200) = 3.5%). Both methods reach 3.5% at
  // their finest run, n = 3200: the ratio there is 1e-5 3200^2 / (1e-3 3200) = 32.
  const nlohmann::json j = sweep_fits(synthetic_sweep(), 0.01);
  EXPECT_FALSE(j["methods"]["full"]["time_to_target_error"]["reached"].get<bool>());
  EXPECT_FALSE(j["speedup"].contains("full_over_hierarchical_interpolated"));
  const auto& c = j["speedup_at_common_error"];
  EXPECT_NEAR(c["error_l2"].get<double>(), 2.0 / std::sqrt(3200.0), 1e-15);
  EXPECT_NEAR(c["full_over_hierarchical_interpolated"].get<double>(), 32.0, 1e-9);
  EXPECT_NEAR(j["speedup_at_common_error_smooth"]["full_over_hierarchical_interpolated"].get<double>(), 32.0, 1e-9);
}

TEST(SweepFits, BeyondTheRunsTheFitsExtrapolateTheTimeToTheTarget) {
  // Target 1%: error 2 / sqrt(n) reaches it at n* = 40000 (displayed field 1 / sqrt(n): 10000), where
  // the full matrix takes 1e-5 n*^2 = 16000 s and HR 1e-3 n* = 40 s: ratio 400 (displayed: 100).
  const nlohmann::json j = sweep_fits(synthetic_sweep(), 0.01);
  ASSERT_TRUE(j.contains("speedup_extrapolated"));
  const auto& x = j["speedup_extrapolated"];
  EXPECT_NEAR(x["full"]["elements"].get<double>(), 40000.0, 1e-3);
  EXPECT_NEAR(x["full"]["seconds"].get<double>(), 16000.0, 1e-3);
  EXPECT_NEAR(x["hierarchical"]["seconds"].get<double>(), 40.0, 1e-6);
  EXPECT_NEAR(x["full_over_hierarchical"].get<double>(), 400.0, 1e-4);
  EXPECT_NEAR(j["speedup_extrapolated_smooth"]["full_over_hierarchical"].get<double>(), 100.0, 1e-4);
  EXPECT_NE(x["note"].get<std::string>().find("extrapolated"), std::string::npos);
  // Where the runs reach the target, no extrapolation is made.
  EXPECT_FALSE(sweep_fits(synthetic_sweep(), 0.06).contains("speedup_extrapolated"));
}

}  // namespace
}  // namespace hrad
