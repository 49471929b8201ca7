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

/// A segment p0 -> p1 with its unit direction and length, computed once per polygon edge.
struct Segment {
  Vec3 p0, p1, dir;
  double length = 0.0;
};
Segment make_segment(const Vec3& p0, const Vec3& p1);

/// What the closed-form (logarithmic) part of K needs about a segment p and one endpoint Q of the
/// other segment; the two edges meeting at Q share it, so a contour sum computes it once per
/// (edge, vertex) rather than once per edge pair.
struct EndpointTerms {
  double beta = 0.0;                    // (P0 - Q) . a: P(s) is nearest Q at s = -beta
  double rho = 0.0;                     // distance of Q from p's line
  double r2_0 = 0.0, r2_1 = 0.0;        // |P0 - Q|^2, |P1 - Q|^2
  double log0 = 0.0, log1 = 0.0;        // their logarithms (0 where they are 0)
  double h_atan0 = 0.0, h_atan1 = 0.0;  // rho atan(beta / rho), rho atan((Lp + beta) / rho) (0 for rho = 0)
};
EndpointTerms endpoint_terms(const Segment& p, const Vec3& q);

/// |P - Q|^2 and its logarithm (0 where it is 0) for a vertex P of one polygon and Q of the other:
/// the end of one edge and the start of the next share it.
struct VertexPairLog {
  double r2 = 0.0, log = 0.0;
};
VertexPairLog vertex_pair_log(const Vec3& p, const Vec3& q);

/// endpoint_terms(p, q) from vertex_pair_log(p.p0, q) and vertex_pair_log(p.p1, q).
EndpointTerms endpoint_terms(const Segment& p, const Vec3& q, const VertexPairLog& at_p0, const VertexPairLog& at_p1);

/// Unit directions parallel within their rounding (|a x b| <= 1e-15): a tilt of 1e-15 changes K
/// by ~1e-15 Lp Lq, so such pairs take the parallel closed form.
inline bool parallel_directions(const Vec3& axb) { return axb.squaredNorm() <= 1e-30; }

/// K = int_0^Lp int_0^Lq ln |P(s) - Q(t)| ds dt + Lp * Lq for the segments p and q.
/// The added Lp * Lq (the same multiple of Lp * Lq for every pair) cancels in the double sum over
/// two closed contours, as does any change of the unit of length; it is dropped from the closed forms.
/// Exact limits: parallel and collinear segments use the elementary closed form, shared and touching
/// endpoints are integrable log singularities handled by graded quadrature (see the .cpp).
/// `at_q0` and `at_q1` are endpoint_terms(p, q.p0) and endpoint_terms(p, q.p1).
EdgePairIntegral edge_pair_log_integral(const Segment& p, const Segment& q, const EndpointTerms& at_q0,
                                        const EndpointTerms& at_q1);

/// The same from the four endpoints (computes the segments and endpoint terms itself).
EdgePairIntegral edge_pair_log_integral(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

}  // namespace hrad::detail
