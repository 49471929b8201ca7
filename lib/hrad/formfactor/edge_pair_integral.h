// The edge-pair term of the contour-integral form factor (Stokes' theorem applied twice to the
// area-area integral; Sparrow 1963, Schroeder & Hanrahan 1993 eq. 3):
//   A_i F_ij = 1/(2 pi) sum_p sum_q (a_p . b_q) * int_{edge p} int_{edge q} ln r  ds dt.
#pragma once

#include "hrad/core/types.h"

namespace hrad::detail {

struct EdgePairIntegral {
  double value = 0.0;      // K
  double magnitude = 0.0;  // sum of the absolute sizes of the terms K is assembled from
};

/// K = int_0^Lp int_0^Lq ln |P(s) - Q(t)| ds dt + Lp * Lq for the segments P0->P1 and Q0->Q1.
/// The added Lp * Lq (the same multiple of Lp * Lq for every pair) cancels in the double sum over
/// two closed contours, as does any change of the unit of length; it is dropped from the closed forms.
/// Exact limits: parallel and collinear segments use the elementary closed form, shared and touching
/// endpoints are integrable log singularities handled by graded quadrature (see the .cpp).
EdgePairIntegral edge_pair_log_integral(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

}  // namespace hrad::detail
