// The shaft's side facets (shaft_hull.h) against an independent construction: CGAL's convex_hull_3
// of the same points, whose triangles are grouped by plane. Integer corners make the degenerate
// cases common: facets through four or more corners (parallel edges), polygons sharing an edge
// or a vertex, a point against a polygon, and coplanar polygons.
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_3.h>

#include <array>
#include <random>
#include <vector>

#include "hrad/visibility/shaft_hull.h"
#include "support/epick_shaft_ops.h"

namespace hrad::detail {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P = K::Point_3;

using EpickOps = hrad::test::EpickShaftOps;

using Facet = ShaftFacet<EpickOps>;

bool same_plane(const P& p, const P& q, const P& r, const P& a, const P& b, const P& c) {
  return CGAL::coplanar(p, q, r, a) && CGAL::coplanar(p, q, r, b) && CGAL::coplanar(p, q, r, c);
}

/// The distinct planes of CGAL's hull triangles that hold points of both A = pts[0, a_count) and B.
std::vector<std::array<P, 3>> cgal_side_planes(const std::vector<P>& pts, std::size_t a_count) {
  std::vector<P> vertices;
  std::vector<std::array<std::size_t, 3>> faces;
  CGAL::convex_hull_3(pts.begin(), pts.end(), vertices, faces);
  std::vector<std::array<P, 3>> planes;
  for (const auto& f : faces) {
    const P &p = vertices[f[0]], &q = vertices[f[1]], &r = vertices[f[2]];
    bool from_a = false, from_b = false;
    for (std::size_t i = 0; i < pts.size(); ++i)
      if (CGAL::coplanar(p, q, r, pts[i])) (i < a_count ? from_a : from_b) = true;
    if (!from_a || !from_b) continue;
    const bool known = std::any_of(planes.begin(), planes.end(),
                                   [&](const std::array<P, 3>& g) { return same_plane(g[0], g[1], g[2], p, q, r); });
    if (!known) planes.push_back({p, q, r});
  }
  return planes;
}

/// Checks shaft_side_facets() on pts against CGAL's hull: the same planes, each once, each with
/// every point on its non-negative side.
void expect_cgal_facets(const std::vector<P>& pts, std::size_t a_count) {
  const std::vector<Facet> ours = shaft_side_facets<EpickOps>(std::span<const P>(pts), a_count);
  const std::vector<std::array<P, 3>> theirs = cgal_side_planes(pts, a_count);
  ASSERT_EQ(ours.size(), theirs.size());
  for (const Facet& f : ours) {
    for (const P& x : pts) EXPECT_NE(f.side(x), CGAL::NEGATIVE);
    EXPECT_EQ(std::count_if(theirs.begin(), theirs.end(),
                            [&](const std::array<P, 3>& g) { return same_plane(g[0], g[1], g[2], f.p, f.q, f.r); }),
              1);
  }
}

/// A parallelogram o, o + u, o + u + v, o + v (a triangle when `triangle`).
std::vector<P> parallelogram(const std::array<int, 3>& o, const std::array<int, 3>& u, const std::array<int, 3>& v,
                             bool triangle = false) {
  std::vector<P> out{P(o[0], o[1], o[2]), P(o[0] + u[0], o[1] + u[1], o[2] + u[2])};
  if (!triangle) out.emplace_back(o[0] + u[0] + v[0], o[1] + u[1] + v[1], o[2] + u[2] + v[2]);
  out.emplace_back(o[0] + v[0], o[1] + v[1], o[2] + v[2]);
  return out;
}

std::vector<P> join(std::vector<P> a, const std::vector<P>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(ShaftHull, SideFacetsAreCgalConvexHullFacetsOnRandomIntegerPolygons) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coord(-3, 3);
  auto vec = [&] { return std::array<int, 3>{coord(rng), coord(rng), coord(rng)}; };
  int checked = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const auto a = parallelogram(vec(), vec(), vec(), trial % 3 == 0);
    const auto b = parallelogram(vec(), vec(), vec(), trial % 5 == 0);
    const std::vector<P> pts = join(a, b);
    // Degenerate polygons (collinear corners) and coplanar pairs are not shafts' inputs.
    if (CGAL::collinear(a[0], a[1], a.back()) || CGAL::collinear(b[0], b[1], b.back())) continue;
    bool all_coplanar = true;
    for (const P& x : b) all_coplanar &= CGAL::coplanar(a[0], a[1], a.back(), x);
    if (all_coplanar) continue;
    SCOPED_TRACE(trial);
    expect_cgal_facets(pts, a.size());
    ++checked;
  }
  EXPECT_GT(checked, 2000);
}

TEST(ShaftHull, FacingSquaresGiveFourFacetsThroughFourCornersEach) {
  // Unit squares one above the other: the shaft is a cube, each side facet holds an edge of each.
  const auto a = parallelogram({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const auto b = parallelogram({0, 0, 1}, {0, 1, 0}, {1, 0, 0});
  const std::vector<P> pts = join(a, b);
  EXPECT_EQ(shaft_side_facets<EpickOps>(std::span<const P>(pts), 4).size(), 4u);
  expect_cgal_facets(pts, 4);
}

TEST(ShaftHull, NeighboursSharingAnEdgeOrAVertexAndAPointAgainstAPolygon) {
  // Floor and wall meeting along x: the shared edge's plane pair.
  expect_cgal_facets(join(parallelogram({0, 0, 0}, {2, 0, 0}, {0, 2, 0}), parallelogram({0, 0, 0}, {0, 0, 2}, {2, 0, 0})),
                     4);
  // Two squares touching at one corner, at an angle.
  expect_cgal_facets(join(parallelogram({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), parallelogram({1, 1, 0}, {1, 0, 1}, {0, 1, 1})),
                     4);
  // A point above a square: the four sides of the pyramid.
  const std::vector<P> pyramid = join({P(0.5, 0.5, 2.0)}, parallelogram({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  EXPECT_EQ(shaft_side_facets<EpickOps>(std::span<const P>(pyramid), 1).size(), 4u);
  expect_cgal_facets(pyramid, 1);
}

TEST(ShaftHull, CoplanarPolygonsHaveNoShaft) {
  const std::vector<P> pts = join(parallelogram({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), parallelogram({3, 0, 0}, {1, 0, 0}, {0, 2, 0}));
  EXPECT_TRUE(shaft_side_facets<EpickOps>(std::span<const P>(pts), 4).empty());
}

}  // namespace
}  // namespace hrad::detail
