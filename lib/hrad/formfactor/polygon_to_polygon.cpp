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
// The contour sum is tried first (it is the fast path); when its bound says it is not accurate to
// rel_tol (kPolygonToPolygonTolerance by default):
// * a pair far apart relative to its size is integrated directly by product Gauss quadrature of the
//   area-area kernel (far_field_form_factor.cpp), which does not cancel at all;
// * otherwise both polygons are triangulated and the larger triangle of a piece pair is bisected
//   until each piece pair is far apart (Gauss) or its own contour sum is accurate. All pieces lie in
//   each other's front half-space, so every piece value is >= 0 and errors cannot cancel either.
//   Touching pieces of similar size (at a shared edge or vertex) keep their contour sum: there the
//   cancellation comes from the pieces' aspect ratio, and bisection would not remove it
//   (about 1e-16 / aspect relative).
#include "hrad/formfactor/polygon_to_polygon.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "hrad/formfactor/contour_form_factor.h"
#include "hrad/formfactor/far_field_form_factor.h"
#include "hrad/formfactor/polygon_distance.h"
#include "hrad/formfactor/prepared_pair.h"
#include "hrad/formfactor/quadrature_form_factor.h"
#include "hrad/formfactor/triangle_piece.h"
#include "hrad/geometry/polygon.h"

namespace hrad {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// The rounding error of a contour sum is below eps * magnitude (measured on Howell's C-11 and C-14
// over aspect ratios 1e-4..1e4 and distances 1e-3..1e3: actual/bound between 0.003 and 0.3).
// A pair's sum is accepted within rel_tol, a piece's and a Gauss rule's within rel_tol / 10 (the
// Gauss order's bound, far_field_form_factor.h, is itself pessimistic: measured against full-
// precision rules over the urban generator's far pairs, 1e-10 asked gives 3e-11 at worst).
constexpr double kPieceMargin = 0.1;
constexpr double kFarMargin = 0.1;
constexpr std::size_t kMaxPieces = 1500;  // bounds the worst case (~0.1 s)
// Point-factor evaluations the last-resort quadrature may spend (~0.1 s).
constexpr std::size_t kFallbackEvaluations = 1'000'000;
// Touching pieces are split only when one is this much larger than the other.
constexpr double kSizeRatio = 4.0;

using Triangle = detail::TrianglePiece;
using detail::bisect;

// Dual bisection of piece pairs (see the file comment).
struct Refinement {
  Vec3 from_normal, to_normal;
  double rel_tol;
  double abs_floor;  // the scaled absolute accuracy per unit of the smaller piece's area
  std::size_t pieces = 0;

  double refine(const Triangle& a, const Triangle& b) {
    ++pieces;
    const int order = detail::far_field_order((a.centre - b.centre).norm(), a.radius, b.radius, rel_tol * kFarMargin);
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
    if (bound <= std::max({kPieceMargin * rel_tol * sum.area_factor, 1e-15 * std::min(a.area, b.area) / (s * s),
                           kPieceMargin * abs_floor * std::min(a.area, b.area) / (s * s)}) ||
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
    const std::vector<Triangle> tf = detail::triangle_pieces(from, from_normal),
                                tt = detail::triangle_pieces(to, to_normal);
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

PairFormFactor polygon_to_polygon(std::span<const Vec3> from, std::span<const Vec3> to, double rel_tol,
                                  double abs_tol) {
  const detail::PreparedPair pair = detail::prepare_pair(from, to);
  if (!pair.visible) return {};
  Refinement refinement{pair.from_normal, pair.to_normal, rel_tol, abs_tol};
  Vec3 cf, ct;
  double rf, rt;
  centre_and_radius(pair.from, &cf, &rf);
  centre_and_radius(pair.to, &ct, &rt);
  const detail::ContourSum sum = detail::contour_area_factor(pair.from, pair.to);
  double area_factor = sum.area_factor;
  const double floor = abs_tol * std::min(pair.from_area, pair.to_area) / (pair.scale * pair.scale);
  const bool accurate = kEps * sum.magnitude <= std::max(rel_tol * sum.area_factor, floor);
  if (!accurate) {
    const bool far = detail::far_field_order((cf - ct).norm(), rf, rt, rel_tol * kFarMargin) > 0;
    const bool touching_alike = !far && std::max(rf, rt) < kSizeRatio * std::min(rf, rt) &&
                                detail::polygon_distance(pair.from, pair.from_normal, pair.to, pair.to_normal) == 0.0;
    if (!touching_alike) {
      const double refined = refinement.total(pair.from, pair.to);
      // Out of budget (pieces near each other that stay slivers): the contour sum is usually the
      // better value, unless it breaks the physical bound A_from F <= min(A_from, A_to) (F <= 1 both
      // ways): then it is rounding noise (the form-factor JSON fuzzer found F = 4.8e6 for a unit
      // triangle under a 1 x 1e12 quad), and the refined sum, whose pieces are each >= 0, is kept.
      const double bound = std::min(pair.from_area, pair.to_area) / (pair.scale * pair.scale);
      if (refinement.pieces < kMaxPieces || !(area_factor <= bound)) area_factor = refined;
      // Both sums noise (the refined one too ran out of pieces): the adaptive quadrature of
      // Lambert's exact point factor over `from` does not cancel (0.27836 there, against 0.27832
      // for the quad cut at y = 1e3).
      if (!(area_factor <= bound))
        area_factor = quadrature_form_factor(pair.from, pair.to, 1e-9, kFallbackEvaluations).value * pair.from_area /
                      (pair.scale * pair.scale);
    }
  }
  // Whatever the path, a factor is in [0, 1] in both directions.
  area_factor = std::clamp(area_factor * pair.scale * pair.scale, 0.0, std::min(pair.from_area, pair.to_area));
  return {area_factor / pair.from_area, area_factor / pair.to_area};
}

}  // namespace hrad
