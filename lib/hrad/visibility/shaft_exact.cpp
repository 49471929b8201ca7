#include "hrad/visibility/shaft_exact.h"

// GCC 12 reports CGAL's Epic_converter (its optional result) as maybe used uninitialized once
// inlined here; a false positive in CGAL's headers, silenced for this file only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <vector>

namespace hrad::detail {
namespace {

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using P3 = EK::Point_3;

P3 to_exact(const Vec3& v) { return P3(v.x(), v.y(), v.z()); }

}  // namespace

bool triangle_meets_interior(const std::array<Vec3, 3>& t, std::span<const std::array<Vec3, 3>> planes) {
  std::vector<P3> poly{to_exact(t[0]), to_exact(t[1]), to_exact(t[2])};
  std::vector<EK::Plane_3> bounds;
  for (const auto& p : planes) bounds.emplace_back(to_exact(p[0]), to_exact(p[1]), to_exact(p[2]));
  for (const EK::Plane_3& h : bounds) {  // Sutherland-Hodgman, keeping h >= 0
    std::vector<P3> out;
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
      const P3& p = poly[i];
      const P3& q = poly[(i + 1) % n];
      const CGAL::Oriented_side sp = h.oriented_side(p), sq = h.oriented_side(q);
      if (sp != CGAL::ON_NEGATIVE_SIDE) out.push_back(p);
      if ((sp == CGAL::ON_POSITIVE_SIDE && sq == CGAL::ON_NEGATIVE_SIDE) ||
          (sp == CGAL::ON_NEGATIVE_SIDE && sq == CGAL::ON_POSITIVE_SIDE)) {
        const auto x = CGAL::intersection(h, EK::Segment_3(p, q));
        if (x)
          if (const P3* point = boost::get<P3>(&*x)) out.push_back(*point);
      }
    }
    poly = std::move(out);
    if (poly.empty()) return false;
  }
  for (const EK::Plane_3& h : bounds) {
    bool all_on = true;
    for (const P3& p : poly) all_on = all_on && h.has_on(p);
    if (all_on) return false;
  }
  return true;
}

}  // namespace hrad::detail
