// Gauss-Legendre rules on [-1, 1], computed once (Newton on the three-term recurrence).
#pragma once

#include <span>

namespace hrad::detail {

/// Nodes and weights of one rule; both spans have n entries, nodes ascending.
struct GaussRule {
  std::span<const double> nodes;
  std::span<const double> weights;
};

inline constexpr int kMaxGaussOrder = 64;

/// The n-point Gauss-Legendre rule, 1 <= n <= kMaxGaussOrder (Golub & Welsch 1969 give the same
/// nodes; here Newton iteration on P_n from the asymptotic initial guess, Abramowitz & Stegun 22.16.6).
GaussRule gauss_legendre(int n);

}  // namespace hrad::detail
