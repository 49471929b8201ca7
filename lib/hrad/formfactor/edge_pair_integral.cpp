// K_pq = int int ln r ds dt + Lp Lq over two segments, semi-analytically:
//
// * Inner integral over t in closed form (Sparrow 1963; Schroeder & Hanrahan 1993, eq. 7):
//     int_0^Lq ln|w - t b| dt = [ u/2 ln(u^2 + h^2) - u + h atan(u/h) ]_{u0}^{u1},
//   w = P(s) - Q0, u0 = -w.b, u1 = Lq - w.b, h = |w x b| (distance of P(s) from q's line).
// * Outer integral of the logarithmic part in closed form as well: u is linear in s and
//   u^2 + h^2 = |P(s) - Q_k|^2 is quadratic, so int u/2 ln(u^2 + h^2) ds is elementary (log and
//   atan). What remains, int h(s) [atan(u1/h) - atan(u0/h)] ds = int h(s) theta(s) ds with theta the
//   angle that segment q subtends at P(s), is the non-elementary (Clausen/dilogarithm) part of
//   Schroeder & Hanrahan's closed form (their eq. 19-21). It is done here by Gauss-Legendre panels
//   chosen from the integrand's complex singularities: h theta is analytic except at
//   P(s) = Q0, P(s) = Q1 (complex s where |P(s) - Q_k|^2 = 0) and at h(s) = 0 (the branch point of
//   the distance to q's line). For each panel the Bernstein ellipse through the nearest of these
//   points gives the number of nodes for 1e-16 (Trefethen 2008, Thm 4.5: error ~ rho^(-2n));
//   panels too close to a singularity are split at it or graded geometrically towards it. Shared
//   and touching endpoints and crossing edges are exact singular points of this kind: h theta stays
//   bounded there (it vanishes like s), so the graded panels converge to rounding.
// * Parallel and collinear segments (b = +-a): everything is elementary (Howell's C-11 derivation):
//     K = T(Lp + d) - T(d) - T(Lp + d - Lq) + T(d - Lq) - Lp Lq / 2,
//     T(x) = (x^2 - h^2)/4 ln(x^2 + h^2) + h x atan(x/h),
//   d the offset of P0 from Q0 along a, h the distance between the lines.
#include "hrad/formfactor/edge_pair_integral.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include <Eigen/Core>

#include "hrad/formfactor/fast_atan2.h"
#include "hrad/formfactor/gauss_legendre.h"

namespace hrad::detail {
namespace {

// x log x style terms vanish at 0; ln(0) must not turn them into NaN.
inline double log_or_zero(double r2) { return r2 > 0.0 ? std::log(r2) : 0.0; }
// h atan(x / h) for h >= 0, as atan2 of |x| and h (no rounding of x / h; fast_atan2.h).
inline double h_atan(double h, double x) { return h > 0.0 ? h * std::copysign(fast_atan2(std::abs(x), h), x) : 0.0; }

// T(x) up to a multiple of x^2 - h^2 that cancels in the four-term sum. With h large against x,
// ln(x^2 + h^2) = ln h^2 + log1p(x^2/h^2): the ln h^2 part sums to Lp Lq ln(h^2) / 2 exactly, and
// log1p keeps the digits that ln(h^2 + tiny) would lose. `magnitude` gets the absolute rounding scale.
double parallel_t(double x, double h, bool split_log, double* magnitude) {
  const double q = 0.25 * (x * x - h * h);
  const double lg = split_log ? std::log1p((x / h) * (x / h)) : log_or_zero(x * x + h * h);
  const double t = q * lg + x * h_atan(h, x);
  *magnitude += std::abs(t) + (split_log ? 0.0 : std::abs(q));  // ln(y) has absolute error ~eps
  return t;
}

EdgePairIntegral parallel_pair(const Vec3& p0, const Vec3& a, double lp, const Vec3& q0, double lq) {
  const Vec3 w0 = p0 - q0;
  const double d = w0.dot(a);
  const double h = w0.cross(a).norm();
  const double xs[4] = {lp + d, d, lp + d - lq, d - lq};
  const double reach = std::max(std::max(std::abs(xs[0]), std::abs(xs[1])), std::max(std::abs(xs[2]), std::abs(xs[3])));
  const bool split_log = h > 0.5 * reach;
  double magnitude = 0.5 * lp * lq;
  double value = parallel_t(xs[0], h, split_log, &magnitude) - parallel_t(xs[1], h, split_log, &magnitude) -
                 parallel_t(xs[2], h, split_log, &magnitude) + parallel_t(xs[3], h, split_log, &magnitude) -
                 0.5 * lp * lq;
  if (split_log) {
    const double lh = 0.5 * lp * lq * std::log(h * h);
    value += lh;
    magnitude += std::abs(lh);
  }
  return {value, magnitude};
}

// int over sigma in [s0, s1] of (alpha - c sigma)/2 ln(sigma^2 + rho^2), s0 = beta, s1 = Lp + beta,
// from the endpoint terms (whose r2 are the squared distances computed directly).
// Adds the absolute sizes of its terms to *magnitude.
double log_part(double alpha, double c, double lp, const EndpointTerms& t, double* magnitude) {
  const double s0 = t.beta, s1 = lp + t.beta;
  const double a1 = 0.5 * s1 * t.log1 - s1 + t.h_atan1, a0 = 0.5 * s0 * t.log0 - s0 + t.h_atan0;
  const double b1 = 0.25 * t.r2_1 * t.log1 - 0.25 * s1 * s1, b0 = 0.25 * t.r2_0 * t.log0 - 0.25 * s0 * s0;
  // Each ln carries an absolute rounding error ~eps: count its coefficients too.
  *magnitude += std::abs(alpha) * (std::abs(a1) + std::abs(a0) + 0.5 * (std::abs(s1) + std::abs(s0))) +
                std::abs(c) * (std::abs(b1) + std::abs(b0) + 0.25 * (t.r2_1 + t.r2_0));
  return alpha * (a1 - a0) - c * (b1 - b0);
}

// A singular point re + i im (im >= 0; its conjugate is one too) of h theta in the s plane.
struct Singularity {
  double re, im2;  // re and im^2
};

// h theta along p as scalar polynomials in s, fixed per edge pair, so that a Gauss node costs a few
// multiply-adds, one square root and one atan2. With w(s) = P(s) - Q0 = w0 + s a,
// t = s + beta0 (beta0 = w0 . a, so |w|^2 = t^2 + rho0^2) and c = a . b:
//   w . (w - Lq b) = t^2 + rho0^2 - Lq (w . b),  w . b = (w0 . b - beta0 c) + t c,
//   h^2 = |w0 x b + s (a x b)|^2 = |a x b|^2 ((s - s*)^2 + im^2),
// s* + i im being the branch point of h. Both are sums of squares about their minima, so they
// round no worse than the vector forms they replace.
struct SkewPair {
  double beta0;   // t = s + beta0
  double lqc;     // Lq c
  double x0;      // w . (w - Lq b) at t = 0: rho0^2 - Lq (w0 . b - beta0 c)
  double s_star;  // real part of the branch point of h
  double im2;     // its imaginary part squared
  double naxb;    // |a x b|
  double lq;
  std::array<Singularity, 3> singular;
  int singular_count = 0;
};

// Semi-major axis, in half-lengths of [lo, hi], of the ellipse with foci lo and hi through z: the
// Bernstein ellipse through z has rho = a + sqrt(a^2 - 1) (Trefethen 2013, ATAP ch. 8), which
// grows with a, so the nearest singularity is the one of smallest a. Real arithmetic only.
inline double semi_major(const Singularity& z, double lo, double hi) {
  return (std::sqrt((z.re - lo) * (z.re - lo) + z.im2) + std::sqrt((z.re - hi) * (z.re - hi) + z.im2)) / (hi - lo);
}

constexpr double kLogTarget = 18.5;  // ln(1e16) / 2: nodes n with rho^(-2n) <= 1e-16
constexpr int kMinOrder = 3;
// Up to this many nodes a panel is kept whole: one panel of n(rho) nodes costs less than two
// halves unless the singularity is within about half a panel length of it.
constexpr int kMaxOrder = 32;
static_assert(kMaxOrder <= kMaxGaussOrder);

// fast_atan2 (fast_atan2.h: the same table and series) for y >= 0, with the octant applied in plain
// double arithmetic: within ~1.5 ulp of pi rather than ~1, which the quadrature sum's own rounding
// hides, for a shorter chain per node. 0 for y = x = 0 (and for NaN, which would index the table).
inline double node_atan2(double y, double x) {
  const double ax = std::abs(x);
  const double num = std::min(y, ax), den = std::max(y, ax);
  if (!(den > 0.0)) return 0.0;
  const auto [node, series] = atan_reduced(num / den);
  const double atan_t = node.hi + (node.lo + series);
  // By octant (2 [y > |x|] + [x < 0]): offset + sign atan(t).
  static constexpr std::array<std::array<double, 2>, 4> kOctant = {{
      {0.0, 1.0},
      {3.1415926535897931, -1.0},
      {1.5707963267948966, -1.0},
      {1.5707963267948966, 1.0},
  }};
  const auto& oct = kOctant[static_cast<std::size_t>(2 * int(y > ax) + int(x < 0.0))];
  return oct[0] + oct[1] * atan_t;
}

// The integral of h theta / |a x b| over [lo, hi] by the N-point rule, theta = atan2(h Lq, w . (w - Lq b))
// the angle that q subtends at P(s) (where h = 0 the atan2 is finite and multiplied by 0).
// One instance per N: fixed trip counts, so the loops' exits are predicted (the order changes from
// one edge pair to the next).
template <int N>
double gauss_fixed(const SkewPair& e, double lo, double hi) {
  const GaussRule g = gauss_legendre(N);
  const double half = 0.5 * (hi - lo), mid = 0.5 * (hi + lo);
  const double t_mid = mid + e.beta0, d_mid = mid - e.s_star, y_scale = e.naxb * e.lq;
  // All nodes' roots and arguments first, then the atan2 terms: independent chains, so the
  // square roots overlap with the atan2 polynomials (and Eigen's array square root is the packed
  // instruction, without the scalar call's errno check).
  using Column = Eigen::Array<double, N, 1>;
  const Eigen::Map<const Column> z(g.nodes.data());
  const Column d = d_mid + half * z;
  const Column r = (d * d + e.im2).sqrt();  // h / |a x b|
  const Column t = t_mid + half * z;
  const Column x = t * (t - e.lqc) + e.x0;
  double sum = 0.0;
  for (int i = 0; i < N; ++i) sum += g.weights[i] * (r[i] * node_atan2(r[i] * y_scale, x[i]));
  return sum * half;
}

using GaussFn = double (*)(const SkewPair&, double, double);
template <int... I>
constexpr std::array<GaussFn, sizeof...(I)> gauss_table(std::integer_sequence<int, I...>) {
  return {&gauss_fixed<I + 1>...};
}
constexpr std::array<GaussFn, kMaxOrder> kGauss = gauss_table(std::make_integer_sequence<int, kMaxOrder>{});

inline double gauss(const SkewPair& e, double lo, double hi, int n) {
  return kGauss[static_cast<std::size_t>(n - 1)](e, lo, hi);
}

// The Gauss order for a panel whose nearest singularity has semi-major axis a: the smallest n with
// rho^(-2n) <= 1e-16, i.e. n ln(rho) >= kLogTarget, i.e. a >= cosh(kLogTarget / n) (rho = a +
// sqrt(a^2 - 1), ln rho = acosh a). Thresholds instead of a logarithm per panel; 0 when more
// than kMaxOrder nodes would be needed.
const std::array<double, kMaxOrder + 1> kOrderThreshold = [] {
  std::array<double, kMaxOrder + 1> t{};
  for (int n = 1; n <= kMaxOrder; ++n) t[static_cast<std::size_t>(n)] = std::cosh(kLogTarget / n);
  return t;
}();

int gauss_order(double a) {
  if (!(a >= kOrderThreshold[kMaxOrder])) return 0;
  int n = kMinOrder;
  while (a < kOrderThreshold[static_cast<std::size_t>(n)]) ++n;
  return n;
}

double panels(const SkewPair& e, double lo, double hi, double min_length) {
  // The smallest semi-major axis; a >= sqrt(1 + (2 im / len)^2) (the semi-minor axis is at least
  // the distance from the real axis), which spares the square roots of singularities that cannot win.
  double a = INFINITY;
  int worst = 0;
  const double inv_half2 = 4.0 / ((hi - lo) * (hi - lo));
  for (int k = 0; k < e.singular_count; ++k) {
    if (1.0 + e.singular[k].im2 * inv_half2 >= a * a) continue;
    const double ak = semi_major(e.singular[k], lo, hi);
    if (ak < a) a = ak, worst = k;
  }
  const double len = hi - lo;
  const int order = gauss_order(a);
  if (order > 0) return gauss(e, lo, hi, order);
  // A singularity on a panel already at the minimum length: as many nodes as allowed.
  if (len <= min_length) return gauss(e, lo, hi, kMaxOrder);
  // Split at the singularity's abscissa when it lies well inside, else grade towards the end.
  const double x = e.singular[worst].re;
  double split;
  if (x > lo + 0.05 * len && x < hi - 0.05 * len) {
    split = x;
  } else {
    split = x <= 0.5 * (lo + hi) ? lo + 0.3 * len : hi - 0.3 * len;
  }
  return panels(e, lo, split, min_length) + panels(e, split, hi, min_length);
}

EdgePairIntegral skew_pair(const Segment& p, const Segment& q, const EndpointTerms& at_q0, const EndpointTerms& at_q1,
                           const Vec3& axb) {
  const Vec3& a = p.dir;
  const Vec3& b = q.dir;
  SkewPair e;
  const Vec3 w0 = p.p0 - q.p0;
  const double c = a.dot(b);
  e.beta0 = at_q0.beta;
  e.lq = q.length;
  e.lqc = q.length * c;
  e.x0 = at_q0.rho * at_q0.rho - q.length * (w0.dot(b) - at_q0.beta * c);
  // Logarithmic part, both ends of q: Q0 (sign -1) and Q1 (sign +1).
  double sum = 0.0, magnitude = 0.0;
  for (int k = 0; k < 2; ++k) {
    const EndpointTerms& t = k == 0 ? at_q0 : at_q1;
    const Vec3 v = p.p0 - (k == 0 ? q.p0 : q.p1);  // P0 - Q_k
    const double alpha = -v.dot(b - c * a);
    const double part = log_part(alpha, c, p.length, t, &magnitude);
    sum += k == 0 ? -part : part;
    e.singular[e.singular_count++] = {-t.beta, t.rho * t.rho};  // P(s) = Q_k
  }
  // Branch point of h(s) = |m + s (a x b)|, m = w0 x b (a x b != 0: the pair is not parallel),
  // where |h|^2 is least. im^2 from the remaining vector (not from the distance between the lines,
  // |w0 . (a x b)| / |a x b|, equal in exact arithmetic): s*^2 + im^2 then matches |m|^2 / |a x b|^2
  // to rounding however nearly parallel the edges are.
  const double axb2 = axb.squaredNorm(), inv_axb2 = 1.0 / axb2;
  const Vec3 m = w0.cross(b);
  e.naxb = std::sqrt(axb2);
  e.s_star = -m.dot(axb) * inv_axb2;
  e.im2 = (m + e.s_star * axb).squaredNorm() * inv_axb2;
  if (std::isfinite(e.s_star) && std::isfinite(e.im2)) e.singular[e.singular_count++] = {e.s_star, e.im2};
  const double remainder = e.naxb * panels(e, 0.0, p.length, 1e-9 * p.length);
  return {sum + remainder, magnitude + std::abs(remainder)};
}

}  // namespace

Segment make_segment(const Vec3& p0, const Vec3& p1) {
  const Vec3 d = p1 - p0;
  const double length = d.norm();
  return {p0, p1, length > 0.0 ? Vec3(d / length) : Vec3::Zero(), length};
}

VertexPairLog vertex_pair_log(const Vec3& p, const Vec3& q) {
  const double r2 = (p - q).squaredNorm();
  return {r2, log_or_zero(r2)};
}

EndpointTerms endpoint_terms(const Segment& p, const Vec3& q, const VertexPairLog& at_p0, const VertexPairLog& at_p1) {
  EndpointTerms t;
  const Vec3 v0 = p.p0 - q;
  t.beta = v0.dot(p.dir);
  t.rho = v0.cross(p.dir).norm();
  t.r2_0 = at_p0.r2;
  t.r2_1 = at_p1.r2;
  t.log0 = at_p0.log;
  t.log1 = at_p1.log;
  t.h_atan0 = h_atan(t.rho, t.beta);
  t.h_atan1 = h_atan(t.rho, p.length + t.beta);
  return t;
}

EndpointTerms endpoint_terms(const Segment& p, const Vec3& q) {
  return endpoint_terms(p, q, vertex_pair_log(p.p0, q), vertex_pair_log(p.p1, q));
}

EdgePairIntegral edge_pair_log_integral(const Segment& p, const Segment& q, const EndpointTerms& at_q0,
                                        const EndpointTerms& at_q1) {
  if (p.length == 0.0 || q.length == 0.0) return {};
  const Vec3& a = p.dir;
  const Vec3& b = q.dir;
  const Vec3 axb = a.cross(b);
  if (parallel_directions(axb)) {
    return a.dot(b) > 0.0 ? parallel_pair(p.p0, a, p.length, q.p0, q.length)
                          : parallel_pair(p.p0, a, p.length, q.p1, q.length);
  }
  return skew_pair(p, q, at_q0, at_q1, axb);
}

EdgePairIntegral edge_pair_log_integral(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Segment p = make_segment(p0, p1), q = make_segment(q0, q1);
  if (p.length == 0.0 || q.length == 0.0) return {};
  return edge_pair_log_integral(p, q, endpoint_terms(p, q0), endpoint_terms(p, q1));
}

}  // namespace hrad::detail
