// Exact from-point visibility with 2D Boolean operations. This translation unit is the expensive
// one to compile (Polygon_set_2 over an exact kernel): keep it alone.
#include "hrad/visibility/visible_region.h"

// GCC 12 reports CGAL's Epic_converter (its optional result) as maybe used uninitialized once
// inlined here; a false positive in CGAL's headers, silenced for this file only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/Polygon_with_holes_2.h>

#include <algorithm>
#include <cmath>
#include <list>

namespace hrad {
namespace {

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = EK::FT;
using P3 = EK::Point_3;
using P2 = EK::Point_2;
using Polygon2 = CGAL::Polygon_2<EK>;
using PolygonWithHoles2 = CGAL::Polygon_with_holes_2<EK>;
using PolygonSet2 = CGAL::Polygon_set_2<EK>;

P3 to_exact(const Vec3& v) { return P3(v.x(), v.y(), v.z()); }

/// An oriented plane as the exact affine function h(y) = n . y + d.
struct AffinePlane {
  FT a, b, c, d;
  FT operator()(const P3& y) const { return a * y.x() + b * y.y() + c * y.z() + d; }
  static AffinePlane through(const P3& p, const P3& q, const P3& r) {
    const EK::Plane_3 pl(p, q, r);  // positive side: where p, q, r run counter-clockwise
    return {pl.a(), pl.b(), pl.c(), pl.d()};
  }
  AffinePlane flipped() const { return {-a, -b, -c, -d}; }
};

/// Sutherland-Hodgman: the part of a convex polygon where h >= 0, exactly.
std::vector<P3> clip(const std::vector<P3>& poly, const AffinePlane& h) {
  std::vector<P3> out;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const P3& p = poly[i];
    const P3& q = poly[(i + 1) % n];
    const FT hp = h(p), hq = h(q);
    if (hp >= 0) out.push_back(p);
    if ((hp > 0 && hq < 0) || (hp < 0 && hq > 0)) out.push_back(p + (q - p) * (hp / (hp - hq)));
  }
  return out;
}

/// Drops consecutive duplicates and collinear vertices; what remains is a strictly convex polygon
/// when the input was a (possibly degenerate) convex one.
Polygon2 clean_convex(const std::vector<P2>& pts) {
  std::vector<P2> v;
  for (const P2& p : pts)
    if (v.empty() || v.back() != p) v.push_back(p);
  while (v.size() > 1 && v.front() == v.back()) v.pop_back();
  bool changed = true;
  while (changed && v.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < v.size() && v.size() >= 3; ++i) {
      const std::size_t n = v.size();
      if (CGAL::collinear(v[(i + n - 1) % n], v[i], v[(i + 1) % n])) {
        v.erase(v.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        break;
      }
    }
  }
  Polygon2 poly(v.begin(), v.end());
  if (poly.size() >= 3 && poly.orientation() == CGAL::CLOCKWISE) poly.reverse_orientation();
  return poly;
}

}  // namespace

VisibleRegion visible_region(const Scene& scene, const Vec3& x_in, int patch_x, std::span<const Vec3> source,
                             int source_patch) {
  VisibleRegion result;
  std::vector<P3> src;
  for (const Vec3& v : source) src.push_back(to_exact(v));
  if (src.size() < 3) return result;
  // A non-collinear triple (0, j, k) gives the source's oriented plane.
  std::size_t tj = 0, tk = 0;
  for (std::size_t j = 1; j < src.size() && tk == 0; ++j)
    for (std::size_t k = j + 1; k < src.size(); ++k)
      if (!CGAL::collinear(src[0], src[j], src[k])) {
        tj = j;
        tk = k;
        break;
      }
  if (tk == 0) return result;
  const AffinePlane plane = AffinePlane::through(src[0], src[tj], src[tk]);
  const P3 x = to_exact(x_in);
  const FT hx = plane(x);
  if (hx <= 0) return result;  // x behind or in the source's plane: it sees nothing of its front

  // 2D frame: drop the coordinate where the normal is largest; (axis+1, axis+2) keep the
  // orientation when the normal's component is positive.
  const double na[3] = {std::abs(CGAL::to_double(plane.a)), std::abs(CGAL::to_double(plane.b)),
                        std::abs(CGAL::to_double(plane.c))};
  const int axis = static_cast<int>(std::max_element(na, na + 3) - na);
  const int au = (axis + 1) % 3, av = (axis + 2) % 3;
  auto to_2d = [&](const P3& p) { return P2(p[au], p[av]); };
  const FT normal_axis = axis == 0 ? plane.a : axis == 1 ? plane.b : plane.c;
  auto lift = [&](const P2& p) {  // the point of the source's plane above p
    FT c[3];
    c[au] = p.x();
    c[av] = p.y();
    const FT rest = (axis == 0 ? FT(0) : plane.a * c[0]) + (axis == 1 ? FT(0) : plane.b * c[1]) +
                    (axis == 2 ? FT(0) : plane.c * c[2]) + plane.d;
    c[axis] = -rest / normal_axis;
    return Vec3(CGAL::to_double(c[0]), CGAL::to_double(c[1]), CGAL::to_double(c[2]));
  };

  std::vector<P2> src2;
  for (const P3& p : src) src2.push_back(to_2d(p));
  const Polygon2 source2 = clean_convex(src2);
  if (source2.size() < 3) return result;

  // The pyramid from x over the source: one plane through x and each source edge, oriented so
  // that the source's vertex mean is inside.
  FT mx = 0, my = 0, mz = 0;
  for (const P3& p : src) {
    mx += p.x();
    my += p.y();
    mz += p.z();
  }
  const FT count(static_cast<int>(src.size()));
  const P3 mean(mx / count, my / count, mz / count);
  std::vector<AffinePlane> cone{plane};
  for (std::size_t i = 0; i < src.size(); ++i) {
    const P3& p = src[i];
    const P3& q = src[(i + 1) % src.size()];
    if (p == q) continue;
    AffinePlane side = AffinePlane::through(x, p, q);
    if (side(mean) < 0) side = side.flipped();
    cone.push_back(side);
  }

  std::vector<Polygon2> shadows;
  for (std::size_t pi = 0; pi < scene.patches.size(); ++pi) {
    if (static_cast<int>(pi) == patch_x || static_cast<int>(pi) == source_patch) continue;
    const auto& pv = scene.patches[pi].vertices;
    for (std::size_t i = 1; i + 1 < pv.size(); ++i) {
      std::vector<P3> tri{to_exact(pv[0]), to_exact(pv[i]), to_exact(pv[i + 1])};
      if (CGAL::collinear(tri[0], tri[1], tri[2])) continue;
      if (CGAL::orientation(tri[0], tri[1], tri[2], x) == CGAL::COPLANAR) continue;  // projects to a segment
      if (plane(tri[0]) == 0 && plane(tri[1]) == 0 && plane(tri[2]) == 0) continue;  // in the source's plane
      std::vector<P3> clipped = tri;
      for (const AffinePlane& h : cone) {
        clipped = clip(clipped, h);
        if (clipped.size() < 3) break;
      }
      if (clipped.size() < 3) continue;
      // Central projection from x onto the source's plane: y -> x + (y - x) hx / (hx - h(y)).
      // Inside the pyramid h(y) < hx for every y != x, and x is not on the triangle.
      std::vector<P2> proj;
      for (const P3& y : clipped) proj.push_back(to_2d(x + (y - x) * (hx / (hx - plane(y)))));
      Polygon2 shadow = clean_convex(proj);
      if (shadow.size() >= 3) shadows.push_back(std::move(shadow));
    }
  }

  PolygonSet2 visible(source2);
  if (!shadows.empty()) {
    PolygonSet2 occluded;
    occluded.join(shadows.begin(), shadows.end());
    visible.difference(occluded);
  }
  std::list<PolygonWithHoles2> pieces;
  visible.polygons_with_holes(std::back_inserter(pieces));
  const bool flip = normal_axis < 0;  // the 2D frame mirrors the source's orientation
  FT area = 0;
  auto lift_ring = [&](const Polygon2& ring) {
    std::vector<Vec3> out;
    for (auto it = ring.vertices_begin(); it != ring.vertices_end(); ++it) out.push_back(lift(*it));
    if (flip) std::reverse(out.begin(), out.end());
    return out;
  };
  for (const PolygonWithHoles2& piece : pieces) {
    PolygonWithHoles3 p3;
    p3.outer = lift_ring(piece.outer_boundary());
    area += piece.outer_boundary().area();
    for (auto h = piece.holes_begin(); h != piece.holes_end(); ++h) {
      p3.holes.push_back(lift_ring(*h));
      area += h->area();  // holes run clockwise: negative area
    }
    result.pieces.push_back(std::move(p3));
  }
  result.area_fraction = CGAL::to_double(area / source2.area());
  return result;
}

}  // namespace hrad
