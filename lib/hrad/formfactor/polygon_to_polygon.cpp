// Polygon to polygon form factor (see the header).
//
// Method. After mutual clipping (prepared_pair.cpp), in coordinates relative to a vertex of `from`
// and scaled by the pair's size (so the result does not depend on the unit of length),
// A_from F_from_to is the double contour integral of Schroeder & Hanrahan 1993 (eq. 3):
// contour_form_factor.cpp, each edge pair done semi-analytically in edge_pair_integral.cpp (inner
// integral and the outer logarithmic part in closed form, the Clausen-type remainder by
// singularity-aware Gauss-Legendre panels; elementary closed form for parallel and collinear edges).
// The sum comes with the size of its terms, hence a bound on its rounding error.
//
// The contour sum cancels when the factor is small against the edge terms: pairs far apart
// (~1e-12 relative at distance/size 10, ~1e-8 at 1000), pairs of very different size, long slivers.
// When its bound says it is not accurate to kAcceptTolerance:
// * a pair far apart relative to its size is integrated directly by product Gauss quadrature of the
//   area-area kernel (far_field_form_factor.cpp), which does not cancel at all;
// * otherwise both polygons are triangulated and the larger triangle of a piece pair is bisected
//   until each piece pair is far apart (Gauss) or its own contour sum is accurate. All pieces lie in
//   each other's front half-space, so every piece value is >= 0 and errors cannot cancel either.
//   Touching pieces of similar size (at a shared edge or vertex) keep their contour sum: there the
//   cancellation comes from the pieces' aspect ratio, and bisection would not remove it
//   (about 1e-16 / aspect relative).
#include "hrad/formfactor/polygon_to_polygon.h"

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "hrad/formfactor/contour_form_factor.h"
#include "hrad/formfactor/far_field_form_factor.h"
#include "hrad/formfactor/polygon_distance.h"
#include "hrad/formfactor/prepared_pair.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The rounding error of a contour sum is below eps * magnitude (measured on Howell's C-11 and C-14
// over aspect ratios 1e-4..1e4 and distances 1e-3..1e3: actual/bound between 0.003 and 0.3).
constexpr double kAcceptTolerance = 1e-11;
constexpr double kPieceTolerance = 1e-12;
constexpr std::size_t kMaxPieces = 4000;  // bounds the worst case to a few ms
// Touching pieces are split only when one is this much larger than the other.
constexpr double kSizeRatio = 4.0;

struct Triangle {
  std::array<Vec3, 3> v;
  Vec3 centre;
  double radius;
  double area;
};

Triangle make_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  Triangle t{{a, b, c}, (a + b + c) / 3.0, 0.0, 0.5 * (b - a).cross(c - a).norm()};
  for (const Vec3& v : t.v) t.radius = std::max(t.radius, (v - t.centre).norm());
  return t;
}

// Longest-edge bisection, keeping the counter-clockwise order.
std::array<Triangle, 2> bisect(const Triangle& t) {
  int k = 0;
  double longest = -1.0;
  for (int i = 0; i < 3; ++i) {
    const double l = (t.v[(i + 1) % 3] - t.v[i]).squaredNorm();
    if (l > longest) longest = l, k = i;
  }
  const Vec3& a = t.v[k];
  const Vec3& b = t.v[(k + 1) % 3];
  const Vec3& c = t.v[(k + 2) % 3];
  const Vec3 m = 0.5 * (a + b);
  return {make_triangle(a, m, c), make_triangle(m, b, c)};
}

std::vector<Triangle> triangles_of(std::span<const Vec3> p, const Vec3& normal) {
  std::vector<Triangle> out;
  if (is_convex(p, normal)) {
    for (std::size_t i = 1; i + 1 < p.size(); ++i) out.push_back(make_triangle(p[0], p[i], p[i + 1]));
  } else {
    for (const auto& t : triangulate(p, normal)) out.push_back(make_triangle(p[t[0]], p[t[1]], p[t[2]]));
  }
  return out;
}

// Dual bisection of piece pairs (see the file comment).
struct Refinement {
  Vec3 from_normal, to_normal;
  std::size_t pieces = 0;

  double refine(const Triangle& a, const Triangle& b) {
    ++pieces;
    const int order = detail::far_field_order((a.centre - b.centre).norm(), a.radius, b.radius);
    if (order > 0)
      return detail::far_field_area_factor(a.v[0], a.v[1], a.v[2], from_normal, b.v[0], b.v[1], b.v[2], to_normal,
                                           order);
    // The piece pair's contour sum, relative to a vertex and scaled by the pieces' size.
    const double s = std::max(a.radius, b.radius);
    const Vec3& o = a.v[0];
    const std::array<Vec3, 3> la{Vec3::Zero(), (a.v[1] - o) / s, (a.v[2] - o) / s};
    const std::array<Vec3, 3> lb{(b.v[0] - o) / s, (b.v[1] - o) / s, (b.v[2] - o) / s};
    const detail::ContourSum sum = detail::contour_area_factor(la, lb);
    const double value = std::max(0.0, sum.area_factor) * s * s;
    const double bound = kEps * sum.magnitude;
    // Below the floor the piece's factor is noise against its own area, whatever the total.
    if (bound <= std::max(kPieceTolerance * sum.area_factor, 1e-15 * std::min(a.area, b.area) / (s * s)) ||
        pieces >= kMaxPieces)
      return value;
    const double ratio = std::max(a.radius, b.radius) / std::min(a.radius, b.radius);
    if (ratio < kSizeRatio && detail::polygon_distance(a.v, from_normal, b.v, to_normal) == 0.0) return value;
    if (a.radius >= b.radius) {
      const auto halves = bisect(a);
      return refine(halves[0], b) + refine(halves[1], b);
    }
    const auto halves = bisect(b);
    return refine(a, halves[0]) + refine(a, halves[1]);
  }

  double total(std::span<const Vec3> from, std::span<const Vec3> to) {
    double sum = 0.0;
    const std::vector<Triangle> tf = triangles_of(from, from_normal), tt = triangles_of(to, to_normal);
    for (const Triangle& a : tf)
      for (const Triangle& b : tt) sum += refine(a, b);
    return sum;
  }
};

void centre_and_radius(std::span<const Vec3> p, Vec3* centre, double* radius) {
  *centre = Vec3::Zero();
  for (const Vec3& v : p) *centre += v;
  *centre /= double(p.size());
  *radius = 0.0;
  for (const Vec3& v : p) *radius = std::max(*radius, (v - *centre).norm());
}

}  // namespace

PairFormFactor polygon_to_polygon(std::span<const Vec3> from, std::span<const Vec3> to) {
  const detail::PreparedPair pair = detail::prepare_pair(from, to);
  if (!pair.visible) return {};
  Refinement refinement{pair.from_normal, pair.to_normal};
  Vec3 cf, ct;
  double rf, rt;
  centre_and_radius(pair.from, &cf, &rf);
  centre_and_radius(pair.to, &ct, &rt);
  double area_factor = 0.0;
  if (detail::far_field_order((cf - ct).norm(), rf, rt) > 0) {
    area_factor = refinement.total(pair.from, pair.to);
  } else {
    const detail::ContourSum sum = detail::contour_area_factor(pair.from, pair.to);
    area_factor = sum.area_factor;
    const bool accurate = kEps * sum.magnitude <= kAcceptTolerance * sum.area_factor;
    const bool touching_alike = std::max(rf, rt) < kSizeRatio * std::min(rf, rt) &&
                                detail::polygon_distance(pair.from, pair.from_normal, pair.to, pair.to_normal) == 0.0;
    if (!accurate && !touching_alike) {
      const double refined = refinement.total(pair.from, pair.to);
      // Out of budget (pieces near each other that stay slivers): the contour sum is the better value.
      if (refinement.pieces < kMaxPieces) area_factor = refined;
    }
  }
  area_factor = std::max(0.0, area_factor) * pair.scale * pair.scale;
  return {area_factor / pair.from_area, area_factor / pair.to_area};
}

}  // namespace hrad
