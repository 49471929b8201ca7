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
// eps * sum |terms|; when that is not 1e-13 of the result, the polygon is triangulated and bisected
// until each piece is either far from x relative to its size (product Gauss quadrature of the
// kernel cos cos / (pi r^2), which does not cancel; see far_field_form_factor.h for the order) or
// has an accurate Lambert sum of its own.
#include "hrad/formfactor/point_to_polygon.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "hrad/formfactor/clip_polygon.h"
#include "hrad/formfactor/far_field_form_factor.h"
#include "hrad/formfactor/polygon_quadrature.h"
#include "hrad/formfactor/triangle_piece.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kRelTol = 1e-13;
constexpr int kMaxPieces = 2000;  // grazing polygons never get accurate pieces: bound the cost

struct LambertSum {
  double value;
  double magnitude;  // sum of |terms| / (2 pi)
};

// Sum over the closed contour; `r` are the vertices relative to x.
LambertSum lambert_sum(std::span<const Vec3> r, const Vec3& n) {
  double sum = 0.0, magnitude = 0.0;
  const std::size_t k = r.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& a = r[i];
    const Vec3& b = r[i + 1 == k ? 0 : i + 1];
    const Vec3 c = b.cross(a);
    const double s = c.norm();
    // s == 0: x on the edge's line. Outside the segment gamma = 0; on it x would lie in the
    // polygon's plane, which the caller has excluded. Either way the term is 0.
    if (s > 0.0) {
      const double term = std::atan2(s, a.dot(b)) * n.dot(c) / s;
      sum += term;
      magnitude += std::abs(term);
    }
  }
  return {sum / (2.0 * std::numbers::pi), magnitude / (2.0 * std::numbers::pi)};
}

bool accurate(const LambertSum& s) { return kEps * s.magnitude <= kRelTol * s.value; }

// Pieces of the polygon (vertices relative to x, polygon normal `normal`), see the file comment.
struct Refinement {
  Vec3 n, normal;
  int pieces = 0;

  double refine(const detail::TrianglePiece& t) {
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
    const LambertSum s = lambert_sum(t.v, n);
    if (accurate(s) || pieces >= kMaxPieces) return std::max(0.0, s.value);
    const auto halves = detail::bisect(t);
    return refine(halves[0]) + refine(halves[1]);
  }
};

double evaluate(std::span<const Vec3> r, const Vec3& n, const Vec3& normal) {
  const LambertSum s = lambert_sum(r, n);
  if (accurate(s)) return std::max(0.0, s.value);
  Refinement refinement{n, normal.normalized()};
  double sum = 0.0;
  for (const auto& t : detail::triangle_pieces(r, refinement.normal)) sum += refinement.refine(t);
  return sum;
}

}  // namespace

double point_to_polygon(const Vec3& x, const Vec3& n, std::span<const Vec3> polygon) {
  const std::size_t k = polygon.size();
  if (k < 3) return 0.0;
  thread_local std::vector<Vec3> r, clipped;
  thread_local std::vector<double> height;
  r.resize(k);
  height.resize(k);
  bool any_above = false, any_below = false;
  std::size_t nearest = 0;
  double nearest_d2 = INFINITY;
  for (std::size_t i = 0; i < k; ++i) {
    r[i] = polygon[i] - x;
    height[i] = n.dot(r[i]);
    any_above |= height[i] > 0.0;
    any_below |= height[i] < 0.0;
    const double d2 = r[i].squaredNorm();
    if (d2 < nearest_d2) nearest_d2 = d2, nearest = i;
  }
  if (!any_above) return 0.0;  // behind or in the tangent plane
  // x must be strictly in front of the polygon (its plane evaluated at the vertex nearest x).
  const Vec3 normal = newell_normal(r);
  if (!(normal.dot(r[nearest]) < 0.0)) return 0.0;
  if (!any_below) return evaluate(r, n, normal);
  detail::clip_to_half_space(r, height, clipped);
  if (clipped.size() < 3) return 0.0;
  return evaluate(clipped, n, normal);
}

}  // namespace hrad
