// The CGAL visibility oracle: an AABB tree over the scene's triangles, queried with exact
// predicates (Exact_predicates_inexact_constructions_kernel: every predicate below is decided
// exactly on the input doubles; no construction is ever made, so no epsilon is needed).
//
// Touching rules (what "the open segment a-b meets a patch" means):
//   * Occluders are CLOSED: a patch is the union of its fan triangles including their edges and
//     vertices. A segment through a shared edge or vertex of two triangles of an occluding mesh
//     is blocked, so no light passes between the triangles of a closed surface, whatever its
//     tessellation (T-junctions included: the union of closed triangles has no cracks).
//   * The segment is OPEN: its endpoints a and b do not count. A patch that only touches a or b
//     (a neighbouring wall sharing the edge a lies on, the ceiling a coplanar light lies in)
//     does not block. The endpoints' own patches `patch_a` and `patch_b` never block.
//   * Grazing: a segment lying in an occluder's plane is blocked iff it overlaps the closed
//     triangle in more than an endpoint (it runs along the surface or crosses it).
// Pair classification (shaft culling, Haines & Wallace 1994): the shaft of two convex polygons
// A and B is S = conv(A u B), which holds every segment between them; for A, B not coplanar the
// open segments between their relative interiors lie in the interior of S. Only mutually facing
// pairs count (those join A', the part of A in front of B's plane, to B', the part of B in front
// of A's plane), so the shaft used is S cut by the closed front half-spaces of both planes, which
// holds conv(A' u B'). An occluder triangle T
// can hide a set of facing pairs of positive measure only if T meets the shaft's interior:
//   * T is left out when a facet plane of the shaft, or T's own plane, weakly separates them;
//   * T surely meets the interior when its vertices lie strictly inside every facet plane;
//   * otherwise, with VisibilityOptions::exact_shaft_contacts, T is clipped to the shaft in exact
//     rational arithmetic (shaft_exact.h): it misses the interior iff what is left lies in one
//     bounding plane; without, the pair is conservatively partial and sampling decides.
// A pair is fully hidden when one convex planar patch separates A from B strictly and every
// segment between a vertex of A and a vertex of B meets it: the segments between two convex
// polygons cross a plane that separates them inside the convex hull of the vertex-pair
// crossings (central projection maps convex polygons to convex polygons), so all of them meet it.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

#include "hrad/visibility/sampling.h"
#include "hrad/visibility/segment_bvh.h"
#include "hrad/visibility/shaft_exact.h"
#include "hrad/visibility/visibility.h"

namespace hrad {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Segment = K::Segment_3;
using Triangle = K::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, TriangleIterator>;
using AabbTraits = CGAL::AABB_traits<K, Primitive>;
using Tree = CGAL::AABB_tree<AabbTraits>;

Point to_point(const Vec3& v) { return Point(v.x(), v.y(), v.z()); }

/// p lies in the closed triangle t; p is coplanar with t, t is not degenerate.
bool in_closed_coplanar_triangle(const Point& p, const Triangle& t) {
  for (int k = 0; k < 3; ++k)
    if (CGAL::coplanar_orientation(t[k], t[k + 1], t[k + 2], p) == CGAL::NEGATIVE) return false;
  return true;
}

/// a lies in the closed triangle t and b != a is coplanar with it: does the segment leave a into
/// t? Yes iff b is on the inner side of (or on) every edge line through a (the tangent cone of t at a).
bool enters_triangle_from(const Point& a, const Point& b, const Triangle& t) {
  for (int k = 0; k < 3; ++k)
    if (CGAL::coplanar_orientation(t[k], t[k + 1], t[k + 2], a) == CGAL::COLLINEAR &&
        CGAL::coplanar_orientation(t[k], t[k + 1], t[k + 2], b) == CGAL::NEGATIVE)
      return false;
  return true;
}

/// The line through a and b, which lie strictly on opposite sides of t's plane, meets closed t.
bool crossing_inside(const Point& a, const Point& b, const Triangle& t) {
  const CGAL::Orientation s0 = CGAL::orientation(a, b, t[0], t[1]);
  const CGAL::Orientation s1 = CGAL::orientation(a, b, t[1], t[2]);
  const CGAL::Orientation s2 = CGAL::orientation(a, b, t[2], t[0]);
  const bool pos = s0 == CGAL::POSITIVE || s1 == CGAL::POSITIVE || s2 == CGAL::POSITIVE;
  const bool neg = s0 == CGAL::NEGATIVE || s1 == CGAL::NEGATIVE || s2 == CGAL::NEGATIVE;
  return !(pos && neg);
}

/// Exact: the open segment (a, b), a != b, meets the closed non-degenerate triangle t.
bool open_segment_meets_triangle(const Point& a, const Point& b, const Triangle& t) {
  const CGAL::Orientation oa = CGAL::orientation(t[0], t[1], t[2], a);
  const CGAL::Orientation ob = CGAL::orientation(t[0], t[1], t[2], b);
  if (oa == ob && oa != CGAL::COPLANAR) return false;                      // same open side
  if (oa != CGAL::COPLANAR && ob != CGAL::COPLANAR) return crossing_inside(a, b, t);
  if (oa != CGAL::COPLANAR || ob != CGAL::COPLANAR) return false;          // meets the plane at an endpoint only
  // The segment lies in t's plane.
  const bool a_in = in_closed_coplanar_triangle(a, t);
  const bool b_in = in_closed_coplanar_triangle(b, t);
  if (a_in && b_in) return true;
  if (a_in) return enters_triangle_from(a, b, t);
  if (b_in) return enters_triangle_from(b, a, t);
  return CGAL::do_intersect(Segment(a, b), t);  // neither endpoint inside: any contact is interior
}

/// Indices (0, j, k) of a non-collinear vertex triple of a convex polygon (counter-clockwise
/// polygons give a counter-clockwise triple), or {-1, -1, -1} when all vertices are collinear.
std::array<int, 3> plane_triple(std::span<const Point> poly) {
  const int n = static_cast<int>(poly.size());
  int best_j = -1, best_k = -1;
  double best = -1.0;
  for (int j = 1; j < n; ++j)
    for (int k = j + 1; k < n; ++k) {
      const double w = CGAL::cross_product(poly[j] - poly[0], poly[k] - poly[0]).squared_length();
      if (w > best && !CGAL::collinear(poly[0], poly[j], poly[k])) { best = w; best_j = j; best_k = k; }
    }
  if (best_j < 0) return {-1, -1, -1};
  return {0, best_j, best_k};
}

/// Some point of `pts` lies strictly in front of the plane of the polygon `poly`.
bool any_strictly_in_front(std::span<const Point> poly, std::span<const Point> pts) {
  const auto [i, j, k] = plane_triple(poly);
  if (i < 0) return false;
  for (const Point& p : pts)
    if (CGAL::orientation(poly[i], poly[j], poly[k], p) == CGAL::POSITIVE) return true;
  return false;
}

/// A supporting plane of the shaft through three of its points, oriented with the shaft on the
/// non-negative side.
struct Facet {
  Point p, q, r;
  CGAL::Orientation side(const Point& x) const {
    // Shared vertices are common (neighbouring patches) and cost the predicate its exact fallback.
    if (x == p || x == q || x == r) return CGAL::COPLANAR;
    return CGAL::orientation(p, q, r, x);
  }
};

/// The side facet planes of conv(A u B): those through points of both polygons (the planes of A
/// and B themselves are added by the caller as front half-spaces). A facet found from several
/// triples is kept once. Empty when all points are coplanar. O(n^4) in the few corners.
std::vector<Facet> hull_facets(std::span<const Point> pts, std::size_t a_count) {
  std::vector<Facet> facets;
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        if (k < a_count || i >= a_count) continue;  // all from A or all from B: its own plane
        if (CGAL::collinear(pts[i], pts[j], pts[k])) continue;
        bool pos = false, neg = false;
        for (std::size_t m = 0; m < n && !(pos && neg); ++m) {
          if (m == i || m == j || m == k) continue;
          const CGAL::Orientation o = CGAL::orientation(pts[i], pts[j], pts[k], pts[m]);
          pos |= o == CGAL::POSITIVE;
          neg |= o == CGAL::NEGATIVE;
        }
        if (pos && neg) continue;
        if (!pos && !neg) return {};  // all coplanar: no 3D shaft
        // A facet holding more than three points is found once per triple: keep its first.
        const bool known = std::any_of(facets.begin(), facets.end(), [&](const Facet& f) {
          return f.side(pts[i]) == CGAL::COPLANAR && f.side(pts[j]) == CGAL::COPLANAR &&
                 f.side(pts[k]) == CGAL::COPLANAR;
        });
        if (known) continue;
        if (neg) facets.push_back({pts[i], pts[k], pts[j]});
        else facets.push_back({pts[i], pts[j], pts[k]});
      }
  return facets;
}

/// Drops vertices collinear with their neighbours (T-vertices of elements): the hull is the same.
std::vector<Point> corners(std::span<const Vec3> poly) {
  std::vector<Point> all;
  all.reserve(poly.size());
  for (const Vec3& v : poly) all.push_back(to_point(v));
  if (all.size() <= 3) return all;
  std::vector<Point> out;
  const std::size_t n = all.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!CGAL::collinear(all[(i + n - 1) % n], all[i], all[(i + 1) % n])) out.push_back(all[i]);
  return out.size() >= 3 ? out : all;
}

/// Box of some points (exact: the coordinates are the input doubles).
CGAL::Bbox_3 bbox_of(std::span<const Point> pts) {
  CGAL::Bbox_3 box = pts.front().bbox();
  for (const Point& p : pts) box += p.bbox();
  return box;
}

class CgalVisibility final : public Visibility {
 public:
  CgalVisibility(const Scene& scene, const VisibilityOptions& options);

  bool segment_blocked(const Vec3& a, int patch_a, const Vec3& b, int patch_b) const override {
    counters().segment_queries.fetch_add(1, std::memory_order_relaxed);
    return blocked(to_point(a), patch_a, to_point(b), patch_b);
  }

  PairClass classify(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b) const override {
    const PairClass c = classify_corners(corners(a), patch_a, corners(b), patch_b);
    count(c);
    return c;
  }

  PairClass classify_among(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b,
                           const std::vector<int>* candidates, std::vector<int>* occluders) const override {
    const PairClass c = classify_corners(corners(a), patch_a, corners(b), patch_b, candidates, occluders);
    count(c);
    return c;
  }

  bool segment_blocked_among(const Vec3& a, int patch_a, const Vec3& b, int patch_b,
                             std::span<const int> occluders) const override;

  VisibilityEstimate estimate(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b, int samples,
                              std::uint64_t seed) const override;

  VisibilityEstimate estimate_from_point(const Vec3& x, int patch_x, std::span<const Vec3> b, int patch_b, int samples,
                                         std::uint64_t seed) const override;

  bool scene_has_occlusion() const override {
    std::call_once(occlusion_once_, [this] { occlusion_ = decide_occlusion(); });
    return occlusion_;
  }

 private:
  bool blocked(const Point& a, int patch_a, const Point& b, int patch_b) const;
  PairClass classify_corners(std::span<const Point> a, int patch_a, std::span<const Point> b, int patch_b,
                             const std::vector<int>* candidates = nullptr, std::vector<int>* occluders = nullptr) const;
  bool patch_hides(int patch, std::span<const Point> a, std::span<const Point> b) const;
  bool decide_occlusion() const;
  int patch_of(TriangleIterator it) const { return triangle_patch_[it - triangles_.begin()]; }
  void count(PairClass c) const {
    VisibilityCounters& k = counters();
    k.pair_queries.fetch_add(1, std::memory_order_relaxed);
    switch (c) {
      case PairClass::kFacingAway: k.pairs_facing_away.fetch_add(1, std::memory_order_relaxed); break;
      case PairClass::kFullyVisible: k.pairs_visible.fetch_add(1, std::memory_order_relaxed); break;
      case PairClass::kFullyHidden: k.pairs_hidden.fetch_add(1, std::memory_order_relaxed); break;
      case PairClass::kPartial: k.pairs_partial.fetch_add(1, std::memory_order_relaxed); break;
    }
  }

  std::vector<Triangle> triangles_;        ///< non-degenerate fan triangles of all patches
  std::vector<int> triangle_patch_;
  std::vector<CGAL::Bbox_3> triangle_boxes_;
  std::vector<std::pair<int, int>> patch_triangles_;  ///< [begin, end) into triangles_ per patch
  std::vector<char> patch_planar_;         ///< all vertices exactly coplanar
  std::vector<Point> vertices_;            ///< every patch vertex, for the convex-hull test
  double magnitude_ = 0.0;                 ///< largest |coordinate| of the scene
  Tree tree_;
  VisibilityOptions options_;
  detail::SegmentBvh bvh_;                 ///< segment queries (unless options_ ask for tree_)
  std::vector<Triangle> bvh_triangles_;    ///< triangles_ in the hierarchy's leaf order
  std::vector<int> bvh_patch_;
  mutable std::once_flag occlusion_once_;
  mutable bool occlusion_ = true;
};

CgalVisibility::CgalVisibility(const Scene& scene, const VisibilityOptions& options) : options_(options) {
  patch_triangles_.reserve(scene.patches.size());
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    const auto& v = scene.patches[p].vertices;
    const int begin = static_cast<int>(triangles_.size());
    bool planar = true;
    std::array<int, 3> tri{-1, -1, -1};
    std::vector<Point> pts;
    for (const Vec3& x : v) pts.push_back(to_point(x));
    for (const Point& x : pts) {
      vertices_.push_back(x);
      magnitude_ = std::max({magnitude_, std::abs(x.x()), std::abs(x.y()), std::abs(x.z())});
    }
    for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
      const Triangle t(pts[0], pts[i], pts[i + 1]);
      if (t.is_degenerate()) continue;  // a collinear fan triangle lies on an edge of the others
      triangles_.push_back(t);
      triangle_patch_.push_back(static_cast<int>(p));
      triangle_boxes_.push_back(t.bbox());
    }
    tri = plane_triple(pts);
    if (tri[0] >= 0)
      for (const Point& x : pts) planar = planar && CGAL::orientation(pts[tri[0]], pts[tri[1]], pts[tri[2]], x) == CGAL::COPLANAR;
    patch_triangles_.emplace_back(begin, static_cast<int>(triangles_.size()));
    patch_planar_.push_back(planar ? 1 : 0);
  }
  tree_.rebuild(triangles_.cbegin(), triangles_.cend());
  std::vector<detail::Box3> boxes(triangles_.size());
  for (std::size_t i = 0; i < triangles_.size(); ++i)
    for (int k = 0; k < 3; ++k) boxes[i].lo[k] = triangle_boxes_[i].min(k), boxes[i].hi[k] = triangle_boxes_[i].max(k);
  bvh_ = detail::SegmentBvh(boxes);
  for (std::uint32_t i : bvh_.order()) {
    bvh_triangles_.push_back(triangles_[i]);
    bvh_patch_.push_back(triangle_patch_[i]);
  }
}

/// Culling test of a segment against a node's box, in doubles: a slab test on boxes padded by
/// 2^-40 of the largest coordinate magnitude in play (the scene's and the segment's), far more
/// than the test's rounding error, so it never rejects a box the segment meets. It only prunes
/// the traversal; every decision about blocking is made by the exact predicates on triangles.
class SegmentBoxCull {
 public:
  SegmentBoxCull(const Point& a, const Point& b, double scene_magnitude) {
    double m = scene_magnitude;
    for (int k = 0; k < 3; ++k) m = std::max({m, std::abs(a[k]), std::abs(b[k])});
    const double pad = std::ldexp(m, -40) + std::numeric_limits<double>::min();
    for (int k = 0; k < 3; ++k) {
      origin_[k] = a[k];
      const double d = b[k] - a[k];
      flat_[k] = d == 0.0;
      inverse_[k] = flat_[k] ? 0.0 : 1.0 / d;
      pad_t_[k] = flat_[k] ? 0.0 : pad * std::abs(inverse_[k]);
    }
    pad_ = pad;
  }
  bool may_meet(const CGAL::Bbox_3& box) const {
    double t0 = -0x1.0p-30, t1 = 1.0 + 0x1.0p-30;
    for (int k = 0; k < 3; ++k) {
      if (flat_[k]) {
        if (origin_[k] < box.min(k) - pad_ || origin_[k] > box.max(k) + pad_) return false;
        continue;
      }
      double ta = (box.min(k) - origin_[k]) * inverse_[k], tb = (box.max(k) - origin_[k]) * inverse_[k];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta - pad_t_[k]);
      t1 = std::min(t1, tb + pad_t_[k]);
    }
    return t0 <= t1;
  }

 private:
  double origin_[3], inverse_[3], pad_t_[3], pad_;
  bool flat_[3];
};

// Traversal that stops at the first triangle blocking the open segment.
class BlockingTraversal {
 public:
  BlockingTraversal(const std::vector<Triangle>& triangles, const std::vector<int>& patch_of,
                    const std::vector<CGAL::Bbox_3>& boxes, double magnitude, const Point& a, int patch_a,
                    const Point& b, int patch_b)
      : triangles_(triangles), patch_of_(patch_of), boxes_(boxes), a_(a), b_(b), pa_(patch_a), pb_(patch_b),
        cull_(a, b, magnitude) {}
  bool go_further() const { return !blocked_; }
  void intersection(const Segment&, const Primitive& primitive) {
    // CGAL's tree hands over the primitives of a two-primitive node without testing their boxes.
    const std::size_t index = static_cast<std::size_t>(primitive.id() - triangles_.begin());
    const int patch = patch_of_[index];
    if (patch == pa_ || patch == pb_ || !cull_.may_meet(boxes_[index])) return;
    if (open_segment_meets_triangle(a_, b_, *primitive.id())) blocked_ = true;
  }
  template <class Node>
  bool do_intersect(const Segment&, const Node& node) const {
    return cull_.may_meet(node.bbox());
  }
  bool blocked() const { return blocked_; }

 private:
  const std::vector<Triangle>& triangles_;
  const std::vector<int>& patch_of_;
  const std::vector<CGAL::Bbox_3>& boxes_;
  const Point& a_;
  const Point& b_;
  int pa_, pb_;
  SegmentBoxCull cull_;
  bool blocked_ = false;
};

bool CgalVisibility::blocked(const Point& a, int patch_a, const Point& b, int patch_b) const {
  if (a == b || triangles_.empty()) return false;  // the open segment is empty
  if (!options_.cgal_tree_for_segments) {
    const detail::SegmentCull cull({a.x(), a.y(), a.z()}, {b.x(), b.y(), b.z()}, magnitude_);
    return bvh_.any_hit(cull, [&](std::uint32_t i) {
      const int patch = bvh_patch_[i];
      return patch != patch_a && patch != patch_b && open_segment_meets_triangle(a, b, bvh_triangles_[i]);
    });
  }
  BlockingTraversal traversal(triangles_, triangle_patch_, triangle_boxes_, magnitude_, a, patch_a, b, patch_b);
  tree_.traversal(Segment(a, b), traversal);
  return traversal.blocked();
}

bool CgalVisibility::segment_blocked_among(const Vec3& a, int patch_a, const Vec3& b, int patch_b,
                                           std::span<const int> occluders) const {
  counters().segment_queries.fetch_add(1, std::memory_order_relaxed);
  const Point pa = to_point(a), pb = to_point(b);
  if (pa == pb) return false;
  const SegmentBoxCull cull(pa, pb, magnitude_);
  for (const int patch : occluders) {
    if (patch == patch_a || patch == patch_b) continue;
    const auto [begin, end] = patch_triangles_[static_cast<std::size_t>(patch)];
    for (int i = begin; i < end; ++i)
      if (cull.may_meet(triangle_boxes_[static_cast<std::size_t>(i)]) &&
          open_segment_meets_triangle(pa, pb, triangles_[static_cast<std::size_t>(i)]))
        return true;
  }
  return false;
}

// The shaft's bounding planes in doubles, for culling boxes before any exact test (Haines &
// Wallace 1994, shaft culling): a box all of whose points lie on the outer side of one plane, by
// more than a slack many orders above the rounding of the plane's arithmetic, cannot meet the
// shaft. The shaft's box alone lets a long diagonal shaft (across a city) visit most of the scene.
class ShaftPlanes {
 public:
  ShaftPlanes(std::span<const Facet> facets, double scene_magnitude) {
    for (const Facet& f : facets) {
      const Vec3 p(f.p.x(), f.p.y(), f.p.z());
      const Vec3 u = Vec3(f.q.x(), f.q.y(), f.q.z()) - p, v = Vec3(f.r.x(), f.r.y(), f.r.z()) - p;
      const Vec3 n = u.cross(v);  // CGAL::orientation(p, q, r, x) is the sign of n . (x - p)
      // |n . (x - p)| <= |u| |v| |x - p| with |x - p| <= 2 (scene magnitude) for x in the scene;
      // the slack is 2^-30 of that bound, the arithmetic's error a few 2^-52.
      const double bound = u.cwiseAbs().sum() * v.cwiseAbs().sum() * 4.0 * scene_magnitude;
      planes_.push_back({n, n.dot(p), std::ldexp(bound, -30) + std::numeric_limits<double>::min()});
    }
  }
  /// True only when the box lies strictly outside the shaft: every one of its points on the
  /// negative side of some plane.
  bool outside(const CGAL::Bbox_3& box) const {
    for (const Plane& pl : planes_) {
      double top = -pl.offset;
      for (int k = 0; k < 3; ++k) top += pl.normal[k] * (pl.normal[k] > 0.0 ? box.max(k) : box.min(k));
      if (top < -pl.slack) return true;
    }
    return false;
  }

 private:
  struct Plane {
    Vec3 normal;
    double offset, slack;
  };
  std::vector<Plane> planes_;
};

// Decides, triangle by triangle, which patches may meet the shaft's interior and records them in
// `hits`: the test of the top of this file, for the tree traversal and for candidate lists alike.
class ShaftTest {
 public:
  ShaftTest(const std::vector<Triangle>& triangles, const std::vector<int>& patch_of, std::span<const Facet> facets,
            std::span<const Point> shaft_points, std::span<const std::pair<Point, Point>> probes, bool exact_contacts,
            int patch_a, int patch_b, std::vector<int>* hits)
      : triangles_(triangles), patch_of_(patch_of), facets_(facets), pts_(shaft_points), probes_(probes),
        exact_contacts_(exact_contacts), pa_(patch_a), pb_(patch_b), hits_(hits) {}

  void operator()(std::size_t index) {
    const int patch = patch_of_[index];
    if (patch == pa_ || patch == pb_) return;
    if (!hits_->empty() && hits_->back() == patch) return;  // the patch's other triangle: already a hit
    const Triangle& t = triangles_[index];
    for (const Facet& f : facets_)
      if (f.side(t[0]) != CGAL::POSITIVE && f.side(t[1]) != CGAL::POSITIVE && f.side(t[2]) != CGAL::POSITIVE)
        return;  // a facet plane weakly separates t from the shaft
    bool pos = false, neg = false;
    for (const Point& p : pts_) {
      const CGAL::Orientation o = CGAL::orientation(t[0], t[1], t[2], p);
      pos |= o == CGAL::POSITIVE;
      neg |= o == CGAL::NEGATIVE;
    }
    if (!(pos && neg)) return;  // t's plane weakly separates the shaft from t
    bool inside = true;
    for (const Facet& f : facets_)
      for (int k = 0; k < 3 && inside; ++k) inside = f.side(t[k]) == CGAL::POSITIVE;
    if (!inside && exact_contacts_ && !probe_segment_hits(t) && !meets_interior_exactly(t)) return;  // touches only
    hits_->push_back(patch);
  }

 private:
  /// Sufficient and exact: some probe segment whose ends lie strictly inside the shaft crosses t
  /// (its ends strictly on both sides of t's plane, the crossing in closed t), so t meets the
  /// interior. The probes are rounded points near the shaft's vertex pairs; a probe end that is
  /// not strictly inside (the exact facet test) is not used.
  bool probe_segment_hits(const Triangle& t) const {
    for (const auto& [u, v] : probes_) {
      const CGAL::Orientation ou = CGAL::orientation(t[0], t[1], t[2], u);
      const CGAL::Orientation ov = CGAL::orientation(t[0], t[1], t[2], v);
      if (ou != CGAL::COPLANAR && ov == CGAL::opposite(ou) && crossing_inside(u, v, t)) return true;
    }
    return false;
  }
  static Vec3 to_vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }
  bool meets_interior_exactly(const Triangle& t) const {
    std::vector<std::array<Vec3, 3>> planes;
    for (const Facet& f : facets_) planes.push_back({to_vec(f.p), to_vec(f.q), to_vec(f.r)});
    return detail::triangle_meets_interior({to_vec(t[0]), to_vec(t[1]), to_vec(t[2])}, planes);
  }

  const std::vector<Triangle>& triangles_;
  const std::vector<int>& patch_of_;
  std::span<const Facet> facets_;
  std::span<const Point> pts_;
  std::span<const std::pair<Point, Point>> probes_;
  bool exact_contacts_;
  int pa_, pb_;
  std::vector<int>* hits_;
};

// Traversal that hands every triangle whose box overlaps the shaft's box to a ShaftTest.
class ShaftTraversal {
 public:
  ShaftTraversal(const std::vector<Triangle>& triangles, const std::vector<CGAL::Bbox_3>& boxes,
                 const ShaftPlanes& planes, ShaftTest& test)
      : triangles_(triangles), boxes_(boxes), planes_(planes), test_(test) {}
  bool go_further() const { return true; }
  void intersection(const CGAL::Bbox_3&, const Primitive& primitive) {
    const std::size_t i = static_cast<std::size_t>(primitive.id() - triangles_.begin());
    if (!planes_.outside(boxes_[i])) test_(i);
  }
  template <class Node>
  bool do_intersect(const CGAL::Bbox_3& box, const Node& node) const {
    return CGAL::do_overlap(box, node.bbox()) && !planes_.outside(node.bbox());
  }

 private:
  const std::vector<Triangle>& triangles_;
  const std::vector<CGAL::Bbox_3>& boxes_;
  const ShaftPlanes& planes_;
  ShaftTest& test_;
};

bool CgalVisibility::patch_hides(int patch, std::span<const Point> a, std::span<const Point> b) const {
  const auto [begin, end] = patch_triangles_[patch];
  // Every segment between a vertex of A and a vertex of B crosses the triangles [lo, hi), whose
  // union is convex and planar, strictly between its endpoints.
  auto separates = [&](int lo, int hi) {
    const Triangle& t = triangles_[lo];
    const CGAL::Orientation side_a = CGAL::orientation(t[0], t[1], t[2], a[0]);
    if (side_a == CGAL::COPLANAR) return false;
    for (const Point& p : a)
      if (CGAL::orientation(t[0], t[1], t[2], p) != side_a) return false;
    for (const Point& p : b)
      if (CGAL::orientation(t[0], t[1], t[2], p) != CGAL::opposite(side_a)) return false;
    for (const Point& p : a)
      for (const Point& q : b) {
        bool crossed = false;
        for (int i = lo; i < hi && !crossed; ++i) crossed = crossing_inside(p, q, triangles_[i]);
        if (!crossed) return false;
      }
    return true;
  };
  if (patch_planar_[patch]) return begin < end && separates(begin, end);
  for (int i = begin; i < end; ++i)
    if (separates(i, i + 1)) return true;
  return false;
}

PairClass CgalVisibility::classify_corners(std::span<const Point> a, int patch_a, std::span<const Point> b,
                                           int patch_b, const std::vector<int>* candidates,
                                           std::vector<int>* occluders) const {
  if (occluders != nullptr) occluders->clear();
  // Facing: some point of each must lie strictly in front of the other's plane.
  if (a.size() >= 3 && !any_strictly_in_front(a, b)) return PairClass::kFacingAway;
  if (!any_strictly_in_front(b, a)) return PairClass::kFacingAway;
  std::vector<Point> pts(a.begin(), a.end());
  pts.insert(pts.end(), b.begin(), b.end());
  std::vector<Facet> facets = hull_facets(pts, a.size());
  if (facets.empty()) return PairClass::kFacingAway;  // coplanar: no segment leaves the plane
  // Only mutually facing pairs matter (estimate() counts no other), and they join A' to B' (see
  // the top of this file): the closed front half-spaces of both planes bound their shaft too.
  for (std::span<const Point> poly : {a, b}) {
    if (poly.size() < 3) continue;
    const auto t = plane_triple(poly);
    if (t[0] >= 0) facets.push_back({poly[t[0]], poly[t[1]], poly[t[2]]});
  }
  // Probe segments strictly inside the shaft, near each vertex pair (see probe_segment_hits).
  // The explicit return type matters: deduced, it would be an Eigen expression referring to a
  // Vec3 temporary that dies with the call (AddressSanitizer: stack-use-after-scope).
  auto mean = [](std::span<const Point> p) -> Vec3 {
    double x = 0, y = 0, z = 0;
    for (const Point& q : p) x += q.x(), y += q.y(), z += q.z();
    return Vec3(x, y, z) / double(p.size());
  };
  const Vec3 centre = 0.5 * (mean(a) + mean(b));
  auto toward_centre = [&](const Point& p) {
    return to_point(0.9 * Vec3(p.x(), p.y(), p.z()) + 0.1 * centre);
  };
  auto strictly_inside = [&](const Point& p) {
    return std::all_of(facets.begin(), facets.end(), [&](const Facet& f) { return f.side(p) == CGAL::POSITIVE; });
  };
  std::vector<std::pair<Point, Point>> probes;
  for (const Point& p : a)
    for (const Point& q : b) {
      if (!options_.exact_shaft_contacts) break;
      const Point u = toward_centre(p), v = toward_centre(q);
      if (strictly_inside(u) && strictly_inside(v)) probes.emplace_back(u, v);
    }
  std::vector<int> hits;
  ShaftTest test(triangles_, triangle_patch_, facets, pts, probes, options_.exact_shaft_contacts, patch_a, patch_b,
                 &hits);
  const CGAL::Bbox_3 shaft_box = bbox_of(pts);
  const ShaftPlanes planes(facets, magnitude_);
  if (candidates == nullptr) {
    ShaftTraversal traversal(triangles_, triangle_boxes_, planes, test);
    if (!triangles_.empty()) tree_.traversal(shaft_box, traversal);
  } else {
    for (const int patch : *candidates) {
      if (patch == patch_a || patch == patch_b) continue;
      const auto [begin, end] = patch_triangles_[static_cast<std::size_t>(patch)];
      for (int i = begin; i < end; ++i) {
        const CGAL::Bbox_3& box = triangle_boxes_[static_cast<std::size_t>(i)];
        if (CGAL::do_overlap(shaft_box, box) && !planes.outside(box)) test(static_cast<std::size_t>(i));
      }
    }
  }
  if (hits.empty()) return PairClass::kFullyVisible;
  std::sort(hits.begin(), hits.end());
  hits.erase(std::unique(hits.begin(), hits.end()), hits.end());
  if (occluders != nullptr) *occluders = hits;
  for (int patch : hits)
    if (patch_hides(patch, a, b)) return PairClass::kFullyHidden;
  return PairClass::kPartial;
}

VisibilityEstimate CgalVisibility::estimate(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b,
                                            int samples, std::uint64_t seed) const {
  VisibilityEstimate e;
  e.pair_class = classify(a, patch_a, b, patch_b);
  switch (e.pair_class) {
    case PairClass::kFacingAway:
    case PairClass::kFullyHidden: e.fraction = 0.0; e.error = 0.0; return e;
    case PairClass::kFullyVisible: e.fraction = 1.0; e.error = 0.0; return e;
    case PairClass::kPartial: break;
  }
  // Only mutually facing point pairs count: (a, b) has positive cosines at both ends iff b lies
  // strictly in front of A's plane and a strictly in front of B's plane, so these pairs form the
  // product of the two clipped polygons; rejection keeps every test exact.
  const std::vector<Point> ca = corners(a), cb = corners(b);
  const auto ta = plane_triple(ca), tb = plane_triple(cb);
  auto in_front = [](std::span<const Point> poly, const std::array<int, 3>& t, const Point& p) {
    return CGAL::orientation(poly[t[0]], poly[t[1]], poly[t[2]], p) == CGAL::POSITIVE;
  };
  const bool a_all_front = std::all_of(ca.begin(), ca.end(), [&](const Point& p) { return in_front(cb, tb, p); });
  const bool b_all_front = std::all_of(cb.begin(), cb.end(), [&](const Point& p) { return in_front(ca, ta, p); });
  detail::Rng rng(seed);
  std::vector<Vec2> ua, ub;
  detail::stratified_unit_square(samples, rng, &ua);
  detail::stratified_unit_square(samples, rng, &ub);
  const detail::PolygonSampler sa(a), sb(b);
  int visible = 0, facing = 0;
  for (int i = 0; i < samples; ++i) {
    const Point pa = to_point(sa.point(ua[i].x(), ua[i].y()));
    const Point pb = to_point(sb.point(ub[i].x(), ub[i].y()));
    if (!a_all_front && !in_front(cb, tb, pa)) continue;
    if (!b_all_front && !in_front(ca, ta, pb)) continue;
    ++facing;
    visible += blocked(pa, patch_a, pb, patch_b) ? 0 : 1;
  }
  counters().segment_queries.fetch_add(static_cast<std::uint64_t>(facing), std::memory_order_relaxed);
  if (facing == 0) {  // the facing parts are too small for these samples to find
    e.fraction = 0.0;
    e.error = 0.5;
    return e;
  }
  e.fraction = double(visible) / facing;
  e.error = detail::fraction_error(visible, facing);
  return e;
}

VisibilityEstimate CgalVisibility::estimate_from_point(const Vec3& x, int patch_x, std::span<const Vec3> b,
                                                       int patch_b, int samples, std::uint64_t seed) const {
  counters().point_queries.fetch_add(1, std::memory_order_relaxed);
  VisibilityEstimate e;
  const Point px = to_point(x);
  e.pair_class = classify_corners(std::span<const Point>(&px, 1), patch_x, corners(b), patch_b);
  switch (e.pair_class) {
    case PairClass::kFacingAway:
    case PairClass::kFullyHidden: e.fraction = 0.0; e.error = 0.0; return e;
    case PairClass::kFullyVisible: e.fraction = 1.0; e.error = 0.0; return e;
    case PairClass::kPartial: break;
  }
  detail::Rng rng(seed);
  std::vector<Vec2> ub;
  detail::stratified_unit_square(samples, rng, &ub);
  const detail::PolygonSampler sb(b);
  int visible = 0;
  for (const Vec2& s : ub) visible += blocked(px, patch_x, to_point(sb.point(s.x(), s.y())), patch_b) ? 0 : 1;
  counters().segment_queries.fetch_add(static_cast<std::uint64_t>(std::max(samples, 0)), std::memory_order_relaxed);
  e.fraction = samples > 0 ? double(visible) / samples : 0.5;
  e.error = samples > 0 ? detail::fraction_error(visible, samples) : 0.5;
  return e;
}

// No patch can block a segment between points of two patches that see each other (positive
// cosines at both ends) when every patch's plane supports the convex hull of the scene with the
// whole scene on its front side: both endpoints then lie in the closed front half-space of any
// third patch, so the open segment meets its plane only if it lies in that plane (a grazing
// segment, of zero cosine). Tested exactly against the hull's vertices.
bool CgalVisibility::decide_occlusion() const {
  if (triangles_.empty()) return false;
  std::vector<Point> hull;
  const Triangle& t0 = triangles_.front();
  const bool flat = std::all_of(vertices_.begin(), vertices_.end(), [&](const Point& p) {
    return CGAL::orientation(t0[0], t0[1], t0[2], p) == CGAL::COPLANAR;
  });
  if (flat) return false;  // every segment between two patches lies in their common plane
  CGAL::extreme_points_3(vertices_, std::back_inserter(hull));
  for (const Triangle& t : triangles_)
    for (const Point& h : hull)
      if (CGAL::orientation(t[0], t[1], t[2], h) == CGAL::NEGATIVE) return true;
  return false;
}

}  // namespace

std::unique_ptr<Visibility> make_visibility(const Scene& scene, const VisibilityOptions& options) {
  return std::make_unique<CgalVisibility>(scene, options);
}

std::unique_ptr<Visibility> make_visibility(const Scene& scene) { return make_visibility(scene, VisibilityOptions{}); }

}  // namespace hrad
