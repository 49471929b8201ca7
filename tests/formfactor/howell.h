// Closed-form configuration factors from Howell's catalog (J. R. Howell, "A Catalog of Radiation
// Heat Transfer Configuration Factors", 3rd ed., and Howell, Menguc & Siegel, "Thermal Radiation
// Heat Transfer", 6th ed., appendix C), written from the formulas and evaluated in quad precision
// (__float128), because the formulas themselves cancel at extreme aspect ratios.
#pragma once

#include <vector>

#include "hrad/core/types.h"

// The libquadmath functions used, declared here: quadmath.h lives in GCC's own include folder,
// which clang (the sanitizer tree's compiler) does not search. The library is the same.
extern "C" {
__float128 atanq(__float128) noexcept;
__float128 logq(__float128) noexcept;
__float128 sqrtq(__float128) noexcept;
}

namespace hrad::test {

using Quad = __float128;
inline const Quad kPiQ = 4 * atanq(Quad(1));

/// C-11: parallel, directly opposed rectangles a x b at distance c.
inline double howell_c11(double a, double b, double c) {
  const Quad x = Quad(a) / c, y = Quad(b) / c, x2 = x * x, y2 = y * y;
  const Quad t = logq(sqrtq((1 + x2) * (1 + y2) / (1 + x2 + y2))) + x * sqrtq(1 + y2) * atanq(x / sqrtq(1 + y2)) +
                 y * sqrtq(1 + x2) * atanq(y / sqrtq(1 + x2)) - x * atanq(x) - y * atanq(y);
  return double(2 / (kPiQ * x * y) * t);
}

/// C-14: perpendicular rectangles with a common edge of length l; from has width w, to height h.
inline double howell_c14(double l, double w, double h) {
  const Quad H = Quad(h) / l, W = Quad(w) / l, H2 = H * H, W2 = W * W, S = sqrtq(H2 + W2);
  const Quad t = W * atanq(1 / W) + H * atanq(1 / H) - S * atanq(1 / S);
  const Quad lg = logq((1 + W2) * (1 + H2) / (1 + W2 + H2)) + W2 * logq(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2))) +
                  H2 * logq(H2 * (1 + H2 + W2) / ((1 + H2) * (H2 + W2)));
  return double((t + lg / 4) / (kPiQ * W));
}

/// B-3: plane element to a parallel rectangle a x b, the element's normal through a corner, at distance c.
inline double howell_b3(double a, double b, double c) {
  const Quad x = Quad(a) / c, y = Quad(b) / c;
  const Quad sx = sqrtq(1 + x * x), sy = sqrtq(1 + y * y);
  return double((x / sx * atanq(y / sx) + y / sy * atanq(x / sy)) / (2 * kPiQ));
}

/// Plane element to a rectangle in a perpendicular plane (Howell B-2 family): the rectangle spans a
/// along the element's plane and b along its normal, with one edge of length a in the element's plane
/// at distance c, the element on the perpendicular from that edge's end.
///   F = 1/(2 pi) [atan(X) - atan(X / sqrt(1 + Y^2)) / sqrt(1 + Y^2)],  X = a/c, Y = b/c.
inline double howell_perpendicular_element(double a, double b, double c) {
  const Quad x = Quad(a) / c, y = Quad(b) / c, sy = sqrtq(1 + y * y);
  return double((atanq(x) - atanq(x / sy) / sy) / (2 * kPiQ));
}

inline double relative_error(double value, double exact) { return std::abs(value - exact) / std::abs(exact); }

}  // namespace hrad::test
