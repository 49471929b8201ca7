// The side facets of a shaft: the planes of conv(A u B) through points of both polygons (shaft
// culling, Haines & Wallace 1994; cgal_visibility.cpp adds the planes of A and B). Templated on the
// predicates `Ops` (orient, collinear on Ops::P), so that one enumeration serves the double
// points and the exact points on patches (cgal_visibility.cpp, DoubleOps and PatchOps), each
// decided exactly. Included by the visibility sources and their tests.
//
// Why not CGAL::convex_hull_3: it takes a kernel's points, and the exact points on patches would
// need a traits class of their own; for a shaft's eight corners its quickhull is slower than
// this enumeration (shaft_hull_benchmark), and ShaftHull.SideFacetsAreCgalConvexHullFacets* checks
// the enumeration against it.
#pragma once

#include <CGAL/enum.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

namespace hrad::detail {

/// A supporting plane of the shaft through three of its points, oriented with the shaft on the
/// non-negative side.
template <class Ops>
struct ShaftFacet {
  typename Ops::P p, q, r;
  CGAL::Orientation side(const typename Ops::P& x) const {
    // Shared vertices are common (neighbouring patches) and cost the predicate its exact fallback.
    if constexpr (requires { x == p; })
      if (x == p || x == q || x == r) return CGAL::COPLANAR;
    return Ops::orient(p, q, r, x);
  }
};

/// The facet planes of conv(pts) through points of both A = pts[0, a_count) and B = the rest: a
/// triple with points of both sets spans a facet iff no point lies strictly on one side of its
/// plane while another lies strictly on the other. Empty when all points are coplanar (no 3D
/// shaft). Every triple of the n <= 64 corners (at most 8 for two quads: 48 triples) is tried,
/// except those whose points all lie in a facet already found: a facet through four or more
/// corners (parallel edges, as between the elements of facing axis-aligned walls) is found once,
/// and its corners' coplanarity, the predicates' costly exact case, is decided once.
template <class Ops>
std::vector<ShaftFacet<Ops>> shaft_side_facets(std::span<const typename Ops::P> pts, std::size_t a_count) {
  std::vector<ShaftFacet<Ops>> facets;
  std::vector<std::uint64_t> in_plane;  // per facet, the points in its plane as bits
  const std::size_t n = pts.size();
  if (n > 64) throw std::invalid_argument("shaft_side_facets: more than 64 corners");
  const auto bit = [](std::size_t i) { return std::uint64_t{1} << i; };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        if (k < a_count || i >= a_count) continue;  // all from A or all from B: its own plane
        const std::uint64_t triple = bit(i) | bit(j) | bit(k);
        if (std::any_of(in_plane.begin(), in_plane.end(), [&](std::uint64_t m) { return (m & triple) == triple; }))
          continue;  // a facet found from another triple
        if (Ops::collinear(pts[i], pts[j], pts[k])) continue;
        bool pos = false, neg = false;
        std::uint64_t plane = triple;
        for (std::size_t m = 0; m < n && !(pos && neg); ++m) {
          if (m == i || m == j || m == k) continue;
          const CGAL::Orientation o = Ops::orient(pts[i], pts[j], pts[k], pts[m]);
          pos |= o == CGAL::POSITIVE;
          neg |= o == CGAL::NEGATIVE;
          if (o == CGAL::COPLANAR) plane |= bit(m);
        }
        if (pos && neg) continue;
        if (!pos && !neg) return {};  // all coplanar
        if (neg)
          facets.push_back({pts[i], pts[k], pts[j]});
        else
          facets.push_back({pts[i], pts[j], pts[k]});
        in_plane.push_back(plane);
      }
  return facets;
}

}  // namespace hrad::detail
