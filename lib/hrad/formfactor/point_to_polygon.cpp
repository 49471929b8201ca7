// Differential area to polygon: Lambert's contour formula (Lambert 1760; Nusselt 1928), in the form
//   F = 1/(2 pi) * sum_i gamma_i * n . (R_{i+1} x R_i) / |R_{i+1} x R_i|
// with R_i = v_i - x and gamma_i the angle between R_i and R_{i+1} (Cohen & Wallace 1993, eq. 4.16;
// Baum, Rushmeier & Winget 1989, eq. 4). The sign follows from the polygon's counter-clockwise order
// seen from its front. The formula assumes the whole polygon above x's tangent plane, so the polygon
// is first clipped to that half-space. Everything is relative to x and homogeneous of degree 0 in the
// R_i, so the result does not depend on the unit of length.
//
// The sum cancels when the polygon is small or thin against its distance, or grazes the tangent
// plane (terms ~ angle, result ~ solid angle times cosine). Its rounding error is below
// eps * sum |terms|; when that is not rel_tol (1e-13 by default) of the result, the polygon is
// triangulated and bisected until each piece is either far from x relative to its size (product
// Gauss quadrature of the kernel cos cos / (pi r^2), which does not cancel; see
// far_field_form_factor.h for the order) or has an accurate Lambert sum of its own.
//
// Cost: per edge one cross product, one square root, one atan2 (fast_atan2.h) and one division; the
// relative vertices live on the stack for up to kStackVertices vertices. The common call (no vertex
// behind the tangent plane, no refinement) runs inline: clipping, refinement and the heap path for
// larger polygons are out of line. Quads, the solvers' case, get their own copy with the contour
// loop unrolled and the normal from the diagonals; the branches left on that path are predictable
// (the nearest vertex is a selection). None of this changes a result's bits.
#include "hrad/formfactor/point_to_polygon.h"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "hrad/formfactor/clip_polygon.h"
#include "hrad/formfactor/far_field_form_factor.h"
#include "hrad/formfactor/fast_atan2.h"
#include "hrad/formfactor/polygon_quadrature.h"
#include "hrad/formfactor/triangle_piece.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kMaxPieces = 2000;  // grazing polygons never get accurate pieces: bound the cost
constexpr std::size_t kStackVertices = 16;

struct LambertSum {
  double value;
  double magnitude;  // sum of |terms| / (2 pi)
};

// Edge (a, b) of the contour seen from x: s = |c| with c = b x a, a.b, and n.c. Written out in
// scalars, in Eigen's order of operations (same rounding) without the shuffles its 2-wide packets need.
struct EdgeView {
  double s, dot, n_dot_c;
};

inline EdgeView edge_view(const Vec3& a, const Vec3& b, const Vec3& n) {
  const double cx = b.y() * a.z() - b.z() * a.y(), cy = b.z() * a.x() - b.x() * a.z(),
               cz = b.x() * a.y() - b.y() * a.x();
  return {std::sqrt(cx * cx + cy * cy + cz * cz), a.x() * b.x() + a.y() * b.y() + a.z() * b.z(),
          n.x() * cx + n.y() * cy + n.z() * cz};
}

// Adds the edge's term gamma n.c / |c| to the sum and its magnitude to `magnitude`.
inline void add_term(const EdgeView& e, double& sum, double& magnitude) {
  // s == 0: x on the edge's line. Outside the segment gamma = 0; on it x would lie in the
  // polygon's plane, which the caller has excluded. Either way the term is 0.
  if (e.s > 0.0) {
    // The cosine factor first: its division then runs alongside the atan2.
    const double term = detail::fast_atan2(e.s, e.dot) * (e.n_dot_c / e.s);
    sum += term;
    magnitude += std::abs(term);
  }
}

// Sum over the closed contour; `r` are the vertices relative to x. K > 0 fixes the vertex count at
// compile time (quads, the refinement's triangles): the loops are then unrolled, and all edges'
// views come before the terms, which schedules better (BM_PointToQuad). K = 0 takes r.size(), in
// blocks of the same form.
template <std::size_t K = 0>
inline LambertSum lambert_sum(std::span<const Vec3> r, const Vec3& n) {
  constexpr double kInv2Pi = 0.5 / std::numbers::pi;
  double sum = 0.0, magnitude = 0.0;
  if constexpr (K > 0) {
    std::array<EdgeView, K> edges;
    for (std::size_t i = 0; i < K; ++i) edges[i] = edge_view(r[i], r[i + 1 == K ? 0 : i + 1], n);
    for (const EdgeView& e : edges) add_term(e, sum, magnitude);
  } else {
    constexpr std::size_t kBlock = 8;
    const std::size_t k = r.size();
    std::array<EdgeView, kBlock> edges;
    for (std::size_t start = 0; start < k; start += kBlock) {
      const std::size_t m = std::min(kBlock, k - start);
      for (std::size_t j = 0; j < m; ++j) {
        const std::size_t i = start + j;
        edges[j] = edge_view(r[i], r[i + 1 == k ? 0 : i + 1], n);
      }
      for (std::size_t j = 0; j < m; ++j) add_term(edges[j], sum, magnitude);
    }
  }
  return {sum * kInv2Pi, magnitude * kInv2Pi};
}

// Pieces of the polygon (vertices relative to x, polygon normal `normal`), see the file comment.
struct Refinement {
  Vec3 n, normal;
  double rel_tol;
  int pieces = 0;

  double refine(const detail::TrianglePiece& t) {
    // A piece of zero area (from a repeated vertex) subtends no solid angle; its Lambert sum is 0 and
    // would never pass the test below, spending the whole piece budget.
    if (t.area == 0.0) return 0.0;
    ++pieces;
    const int order = detail::far_field_order(t.centre.norm(), 0.0, t.radius);
    if (order > 0) {
      thread_local std::vector<detail::WeightedPoint> points;
      points.clear();
      detail::triangle_quadrature(t.v[0], t.v[1], t.v[2], order, points);
      double sum = 0.0;
      for (const auto& p : points) {
        const double r2 = p.x.squaredNorm();
        sum += p.weight * std::max(0.0, n.dot(p.x)) * -normal.dot(p.x) / (r2 * r2);
      }
      return sum / std::numbers::pi;
    }
    const LambertSum s = lambert_sum<3>(t.v, n);
    if (kEps * s.magnitude <= rel_tol * s.value || pieces >= kMaxPieces) return std::max(0.0, s.value);
    const auto halves = detail::bisect(t);
    return refine(halves[0]) + refine(halves[1]);
  }
};

// The refinement of a sum that cancels (see the file comment): rare, so kept out of line. `pieces`
// is the polygon to refine, `relative` the whole polygon (relative to x), whose Newell normal
// orients the pieces.
[[gnu::noinline]] double refined_sum(std::span<const Vec3> pieces, std::span<const Vec3> relative, const Vec3& n,
                                     double rel_tol) {
  Refinement refinement{n, newell_normal(relative).normalized(), rel_tol};
  double sum = 0.0;
  for (const auto& t : detail::triangle_pieces(pieces, refinement.normal)) sum += refinement.refine(t);
  return sum;
}

// The Lambert sum of `r` (the polygon `relative`, or its part in front of the tangent plane), refined
// if it cancels beyond rel_tol.
template <std::size_t K = 0>
inline double evaluate(std::span<const Vec3> r, std::span<const Vec3> relative, const Vec3& n, double rel_tol) {
  const LambertSum s = lambert_sum<K>(r, n);
  if (rel_tol == kLambertSumOnly || kEps * s.magnitude <= rel_tol * s.value) return std::max(0.0, s.value);
  return refined_sum(r, relative, n, rel_tol);
}

[[gnu::noinline]] double clipped_sum(std::span<const Vec3> relative, std::span<const double> height, const Vec3& n,
                                     double rel_tol) {
  thread_local std::vector<Vec3> clipped;
  detail::clip_to_half_space(relative, height, clipped);
  if (clipped.size() < 3) return 0.0;
  return evaluate(clipped, relative, n, rel_tol);
}

// point_to_polygon() with the relative vertices and their heights above the tangent plane in
// `r` and `height` (k of each); K as in lambert_sum().
template <std::size_t K = 0>
inline double point_to_polygon(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon, double rel_tol, Vec3* r,
                               double* height) {
  const std::size_t k = K == 0 ? polygon.size() : K;
  bool any_above = false, any_below = false;
  std::size_t nearest = 0;
  double nearest_d2 = INFINITY;
  for (std::size_t i = 0; i < k; ++i) {
    r[i] = polygon[i] - x;
    height[i] = n.dot(r[i]);
    any_above |= height[i] > 0.0;
    any_below |= height[i] < 0.0;
    // A selection, not a branch: which vertex is nearest is unpredictable.
    const double d2 = r[i].squaredNorm();
    const bool nearer = d2 < nearest_d2;
    nearest = nearer ? i : nearest;
    nearest_d2 = nearer ? d2 : nearest_d2;
  }
  if (!any_above) return 0.0;  // behind or in the tangent plane
  const std::span<const Vec3> relative(r, k);
  // Newell's normal. For a quad, newell_normal()'s fan from r[0], (r1-r0)x(r2-r0) + (r2-r0)x(r3-r0),
  // is (r2-r0)x(r3-r1) in exact arithmetic: the diagonals' cross product, without the call. Only
  // its sign is used here (the refinement computes newell_normal() itself, so its bits stay).
  const Vec3 normal = K == 4 ? Vec3((r[2] - r[0]).cross(r[3] - r[1])) : newell_normal(relative);
  // x must be strictly in front of the polygon (its plane evaluated at the vertex nearest x).
  if (!(normal.dot(r[nearest]) < 0.0)) return 0.0;
  if (any_below) return clipped_sum(relative, std::span<const double>(height, k), n, rel_tol);
  return evaluate<K>(relative, relative, n, rel_tol);
}

[[gnu::noinline]] double point_to_large_polygon(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon,
                                                double rel_tol) {
  thread_local std::vector<Vec3> r;
  thread_local std::vector<double> height;
  r.resize(polygon.size());
  height.resize(polygon.size());
  return point_to_polygon(x, n, polygon, rel_tol, r.data(), height.data());
}

}  // namespace

double point_to_polygon(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon, double rel_tol) {
  const std::size_t k = polygon.size();
  if (k < 3) return 0.0;
  if (k > kStackVertices) return point_to_large_polygon(x, n, polygon, rel_tol);
  // The relative vertices live on the stack; a quad has its own unrolled copy of the code.
  std::array<Vec3, kStackVertices> r;
  std::array<double, kStackVertices> height;
  if (k == 4) return point_to_polygon<4>(x, n, polygon, rel_tol, r.data(), height.data());
  return point_to_polygon(x, n, polygon, rel_tol, r.data(), height.data());
}

}  // namespace hrad
