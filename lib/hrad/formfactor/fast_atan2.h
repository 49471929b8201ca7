// atan2 for the kernels' inner loops (the Lambert sum per edge, the Clausen-type remainder per Gauss
// node), where the C library's atan2 took about half the time. Within ~1 ulp, like the library's,
// with a shorter dependency chain (one division; the loops it sits in are latency-bound).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace hrad::detail {

/// One point c of the reduction table: atan(c) as hi + lo (to ~2^-106) and the Taylor coefficients
/// of atan(c + d) - atan(c) = sum_j a[j-1] d^j, j = 1..10.
struct AtanNode {
  double c, hi, lo;
  std::array<double, 10> a;
};
inline constexpr int kAtanIntervals = 64;
/// c = k/64 for k = 0..64, except c = 0 for k = 1 (fast_atan2.cpp).
extern const std::array<AtanNode, kAtanIntervals + 1> kAtanTable;

/// The reduced argument of fast_atan2() and its variants: for t in [0, 1], the nearest table node c
/// and the series atan(t) - atan(c) = a1 d + d^2 (a2 + ... + a10 d^8), d = t - c.
struct AtanReduced {
  const AtanNode& node;
  double series;
};
inline AtanReduced atan_reduced(double t) {
  const AtanNode& node = kAtanTable[static_cast<std::size_t>(static_cast<int>(t * kAtanIntervals + 0.5))];
  // Exact: Sterbenz's lemma (t in [c/2, 2c]) for c > 0, and d = t for c = 0.
  const double d = t - node.c;
  const auto& a = node.a;
  // The inner sum by Estrin's scheme (a short dependency chain); a1 d apart, so that for c = 0
  // (a1 = 1) the leading term is not rounded.
  const double d2 = d * d, d4 = d2 * d2, d8 = d4 * d4;
  const double q =
      ((a[1] + a[2] * d) + d2 * (a[3] + a[4] * d)) + d4 * ((a[5] + a[6] * d) + d2 * (a[7] + a[8] * d)) + d8 * a[9];
  return {node, a[0] * d + d2 * q};
}

/// atan2(y, x) in [0, pi] for y >= 0 and finite arguments (0 for y = x = 0).
/// Table-driven argument reduction (Tang 1990, "Table-driven implementation of the exponential
/// function", ACM TOMS 16(4); Muller, "Elementary Functions", 3rd ed., ch. 6): with
/// t = min(y, |x|) / max(y, |x|) in [0, 1] and c = k/64 the nearest table point,
///   atan(t) = atan(c) + sum_{j=1..10} a_j(c) d^j,  d = t - c,  |d| <= 1/128,
///   a_j(c) = (-1)^(j+1) Im((c + i)^j) / (j (1 + c^2)^j)
/// (the Taylor series of Im log(1 + i t) about c; the first neglected term is below 2^-70). Below
/// t = 3/128 the expansion is about c = 0 (|d| <= 3/128, first neglected term t^11/11 < 2^-57 t),
/// so that atan(c) and the series never cancel by more than a third. The octant is restored with
/// pi/2 - r (y > |x|) and pi - r (x < 0); atan(c), pi/2 and pi are carried as two doubles and added
/// last (Fast2Sum, Dekker 1971), so the result is rounded once.
inline double fast_atan2(double y, double x) {
  // By octant (2 [y > |x|] + [x < 0]): result = offset + sign (atan(c) + series), where
  // offset in {0, pi/2, pi} is carried as {hi, lo} and |offset| >= atan(c).
  static constexpr std::array<std::array<double, 3>, 4> kOctant = {{
      {0.0, 0.0, 1.0},
      {3.1415926535897931, 1.2246467991473532e-16, -1.0},
      {1.5707963267948966, 6.123233995736766e-17, -1.0},
      {1.5707963267948966, 6.123233995736766e-17, 1.0},
  }};
  // Selections by table and min/max rather than branches: the octant is unpredictable in the
  // kernels' loops.
  const double ax = std::abs(x);
  const double num = std::min(y, ax), den = std::max(y, ax);
  if (!(den > 0.0)) return 0.0;
  const auto [node, series] = atan_reduced(num / den);
  const auto& oct = kOctant[static_cast<std::size_t>(2 * int(y > ax) + int(x < 0.0))];
  const double inner_hi = oct[2] * node.hi;
  const double s = oct[0] + inner_hi;
  const double e = inner_hi - (s - oct[0]);  // Fast2Sum: exact low part of oct[0] + inner_hi
  return s + (e + oct[1] + oct[2] * (node.lo + series));
}

}  // namespace hrad::detail
