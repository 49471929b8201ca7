// Reference for tests: Monte Carlo ray casting estimate of a polygon-to-polygon form factor.
#pragma once

#include <cstdint>
#include <span>

#include "hrad/core/types.h"

namespace hrad {

struct MonteCarloFormFactor {
  double value = 0.0;           // F_from_to, the fraction of rays that hit `to`'s front
  double standard_error = 0.0;  // sqrt(value (1 - value) / samples), binomial
};

/// F_from_to as the probability that a ray from a uniform point of `from`, in a cosine-weighted
/// direction of its front hemisphere, hits the front of `to` (Malley's method; Cohen & Wallace
/// 1993, sec. 4.9.2; cosine sampling by projecting the unit disc, Pharr, Jakob & Humphreys,
/// PBR 4th ed., sec. A.5.3). Unbiased; deterministic for a given `seed`. Usage:
///   MonteCarloFormFactor mc = monte_carlo_form_factor(from, to, 1'000'000, 42);
MonteCarloFormFactor monte_carlo_form_factor(std::span<const Vec3> from, std::span<const Vec3> to,
                                             std::uint64_t samples, std::uint64_t seed);

}  // namespace hrad
