// atan2 for the kernels' inner loops (the Lambert sum per edge, the Clausen-type remainder per Gauss
// node), where the C library's atan2 took about half the time. Within ~1 ulp, like the library's.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace hrad::detail {

/// atan2(y, x) in [0, pi] for y >= 0 and finite arguments (0 for y = x = 0).
/// Table-driven argument reduction (Tang 1990; Muller, "Elementary Functions", 3rd ed., sec. 6.3):
/// with t = min(y, |x|) / max(y, |x|) in [0, 1] and c = k/16 the nearest table point (c = 0 below
/// t = 3/32, so that atan(c) and atan(z) never cancel by more than a quarter),
///   atan(t) = atan(c) + atan(z),  z = (t - c) / (1 + t c),  |z| <= 3/32,
/// atan(z) = z - z^3/3 + ... - z^15/15 (the first neglected term, z^17/17, is below 2^-62 z).
/// The octant is restored with pi/2 - r (y > |x|) and pi - r (x < 0). atan(c), pi/2 and pi are
/// carried as two doubles and added last (Fast2Sum, Dekker 1971), so the result is rounded once.
inline double fast_atan2(double y, double x) {
  // {c_k, atan(c_k) hi, lo}: c_k = k/16 except c_1 = 0; hi + lo = atan(c_k) to ~2^-106 (mpmath, 60 digits).
  static constexpr std::array<std::array<double, 3>, 17> kTable = {{
      {0.0, 0.0, 0.0},
      {0.0, 0.0, 0.0},
      {0.125, 0.12435499454676144, -3.1253241424539383e-18},
      {0.1875, 0.18534794999569476, 4.180692268843079e-18},
      {0.25, 0.24497866312686414, 1.0698755618734451e-17},
      {0.3125, 0.30288486837497142, -1.1010827903001369e-17},
      {0.375, 0.35877067027057225, -2.4623815582638635e-17},
      {0.4375, 0.41241044159738732, -1.5876522277706891e-17},
      {0.5, 0.46364760900080609, 2.2698777452961687e-17},
      {0.5625, 0.51238946031073773, -2.5462781472855804e-17},
      {0.625, 0.55859931534356244, -5.4556305485916264e-18},
      {0.6875, 0.60228734613496415, 2.9504307372284023e-17},
      {0.75, 0.64350110879328437, 1.5834785051444286e-17},
      {0.8125, 0.68231655487474807, 6.9432236715600077e-18},
      {0.875, 0.71882999962162453, -2.1478388444456983e-17},
      {0.9375, 0.75315128096219441, -2.4256934659182068e-17},
      {1.0, 0.78539816339744828, 3.061616997868383e-17},
  }};
  // By octant (2 [y > |x|] + [x < 0]): result = offset + sign (atan(c) + atan(z)), where
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
  const double t = num / den;
  const auto& row = kTable[static_cast<std::size_t>(t * 16.0 + 0.5)];
  const double c = row[0];
  // t - c is exact (Sterbenz) for c >= 1/8 and trivially for c = 0.
  const double z = (t - c) / (1.0 + t * c);
  const double z2 = z * z;
  const double p = -1.0 / 3 +
                   z2 * (1.0 / 5 + z2 * (-1.0 / 7 + z2 * (1.0 / 9 + z2 * (-1.0 / 11 + z2 * (1.0 / 13 - z2 * (1.0 / 15))))));
  const double atan_z = z + z * z2 * p;
  const auto& oct = kOctant[static_cast<std::size_t>(2 * int(y > ax) + int(x < 0.0))];
  const double inner_hi = oct[2] * row[1];
  const double s = oct[0] + inner_hi;
  const double e = inner_hi - (s - oct[0]);  // Fast2Sum: exact low part of oct[0] + inner_hi
  return s + (e + oct[1] + oct[2] * (row[2] + atan_z));
}

}  // namespace hrad::detail
