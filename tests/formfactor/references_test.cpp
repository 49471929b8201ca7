// The two references against Howell's closed forms: the adaptive quadrature reaches its tolerance,
// the Monte Carlo estimate lies within a few standard errors and its error shrinks like 1/sqrt(N).
#include <gtest/gtest.h>

#include "howell.h"
#include "hrad/formfactor/quadrature_form_factor.h"
#include "support/monte_carlo_form_factor.h"
#include "test_geometry.h"

namespace hrad::test {
namespace {

TEST(QuadratureReference, MeetsItsToleranceOnHowell) {
  for (double c : {0.2, 1.0, 5.0}) {
    const Polygon from = rectangle(Vec3::Zero(), Vec3(1.5, 0, 0), Vec3(0, 1, 0));
    const Polygon to = rectangle(Vec3(0, 0, c), Vec3(0, 1, 0), Vec3(1.5, 0, 0));
    for (double tol : {1e-6, 1e-10}) {
      const QuadratureFormFactor q = quadrature_form_factor(from, to, tol);
      EXPECT_TRUE(q.converged);
      EXPECT_LE(relative_error(q.value, howell_c11(1.5, 1.0, c)), tol) << c << " " << tol;
    }
  }
  // Shared edge (C-14): the log singularity of the point factor at the edge.
  const Polygon floor = rectangle(Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 0.8, 0));
  const Polygon wall = rectangle(Vec3::Zero(), Vec3(0, 0, 1.2), Vec3(1, 0, 0));
  const QuadratureFormFactor q = quadrature_form_factor(floor, wall, 1e-9);
  EXPECT_TRUE(q.converged);
  EXPECT_LE(relative_error(q.value, howell_c14(1.0, 0.8, 1.2)), 1e-9);
}

TEST(MonteCarloReference, WithinItsStandardError) {
  const Polygon floor = rectangle(Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 0.8, 0));
  const Polygon wall = rectangle(Vec3::Zero(), Vec3(0, 0, 1.2), Vec3(1, 0, 0));
  const Polygon ceiling = rectangle(Vec3(0, 0, 0.5), Vec3(0, 0.8, 0), Vec3(1, 0, 0));
  const double exact_wall = howell_c14(1.0, 0.8, 1.2), exact_ceiling = howell_c11(1.0, 0.8, 0.5);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const MonteCarloFormFactor a = monte_carlo_form_factor(floor, wall, 200000, seed);
    const MonteCarloFormFactor b = monte_carlo_form_factor(floor, ceiling, 200000, seed);
    EXPECT_NEAR(a.value, exact_wall, 5.0 * a.standard_error);
    EXPECT_NEAR(b.value, exact_ceiling, 5.0 * b.standard_error);
    EXPECT_NEAR(a.standard_error, std::sqrt(exact_wall * (1 - exact_wall) / 200000), 1e-4);
  }
  // Same seed, same answer.
  EXPECT_EQ(monte_carlo_form_factor(floor, wall, 1000, 9).value, monte_carlo_form_factor(floor, wall, 1000, 9).value);
  // Facing away: never a hit.
  EXPECT_EQ(monte_carlo_form_factor(floor, reversed(wall), 10000, 1).value, 0.0);
}

}  // namespace
}  // namespace hrad::test
