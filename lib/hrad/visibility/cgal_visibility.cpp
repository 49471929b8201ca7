// The CGAL visibility oracle: an AABB tree over the scene's triangles, queried with exact
// predicates (Exact_predicates_inexact_constructions_kernel: every predicate below is decided
// exactly on the input doubles; no construction is ever made, so no epsilon is needed).
//
// Touching rules (what "the open segment a-b meets a patch" means; a and b are the points the
// ends stand for, see "Points on patches" below):
//   * Occluders are CLOSED: a patch is the union of its fan triangles including their edges and
//     vertices. A segment through a shared edge or vertex of two triangles of an occluding mesh
//     is blocked, so no light passes between the triangles of a closed surface, whatever its
//     tessellation (T-junctions included: the union of closed triangles has no cracks).
//   * The segment is OPEN: its endpoints a and b do not count. A patch that only touches a or b
//     (a neighbouring wall sharing the edge a lies on, the ceiling a coplanar light lies in)
//     does not block. The endpoints' own patches `patch_a` and `patch_b` never block.
//   * Grazing: a segment lying in an occluder's plane is blocked iff it overlaps the closed
//     triangle in more than an endpoint (it runs along the surface or crosses it).
// Points on patches. The solvers' points and elements lie on patches only to rounding: a sample
// point or an element's midpoint vertex on a tilted patch is off the patch's plane by an ulp or
// so. Decided on those doubles, a zero-thickness wall's back-to-back twin blocked segments leaving
// the wall whenever the rounding fell behind it (on a turned two-sided box, three quarters of the
// segments across the empty box), and let light through the wall between points whose rounding
// put them on the wrong sides: light leaked into closed boxes. So every point or vertex that names
// its patch stands for the point of the patch's surface with its coordinates on the two axes
// across the patch's dominant normal axis (exactly the double point when that lies on the surface,
// e.g. on an axis-aligned patch), and everything about it is decided exactly: interval arithmetic
// first, exact homogeneous arithmetic when an interval test is undecided (exact_kernels.h,
// on_patch_segment.h, PatchOps below). Facing is decided on these points too (sight()), and
// before any element test on the patches' own vertices (patches_face()): so no pair of points on
// either side of a closed surface of the input can carry light through it, whatever the
// tessellation. The input must be closed in its own doubles: a T-vertex rounded off the edge it
// splits (a tilted wall's vertex computed in doubles) opens a real crack an ulp wide.
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
#include <CGAL/Mpzf.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/convex_hull_3.h>  // extreme_points_3

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <type_traits>
#include <vector>

#include "hrad/geometry/polygon.h"
#include "hrad/visibility/exact_kernels.h"
#include "hrad/visibility/on_patch_segment.h"
#include "hrad/visibility/sampling.h"
#include "hrad/visibility/segment_bvh.h"
#include "hrad/visibility/segment_triangle.h"
#include "hrad/visibility/shaft_exact.h"
#include "hrad/visibility/shaft_hull.h"
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

bool open_segment_meets_triangle(const Point& a, const Point& b, const Triangle& t) {
  return detail::open_segment_meets_triangle<K>(a, b, t);
}
bool crossing_inside(const Point& a, const Point& b, const Triangle& t) { return detail::crossing_inside<K>(a, b, t); }

/// The predicates of the shaft tests on double points (exact predicates on the doubles).
struct DoubleOps {
  using P = Point;
  using Tri = Triangle;
  static CGAL::Orientation orient(const P& a, const P& b, const P& c, const P& d) {
    return CGAL::orientation(a, b, c, d);
  }
  static bool collinear(const P& a, const P& b, const P& c) { return CGAL::collinear(a, b, c); }
  static Vec3 approx(const P& p) { return Vec3(p.x(), p.y(), p.z()); }
};

/// A point exactly on a patch: the double point itself, or its projection onto the plane of one
/// of the patch's triangles along an axis (exact_kernels.h), with an interval enclosure.
struct PatchPoint {
  Point p;
  const detail::Triangle3* plane = nullptr;  ///< null: p itself
  int axis = 0;
  detail::IntervalKernel::Point_3 box;
  mutable std::optional<detail::HomogeneousKernel::Point_3> exact_;
  /// The same point for certain (the converse may fail): shaft facets skip their predicate on it.
  friend bool operator==(const PatchPoint& x, const PatchPoint& y) {
    return x.p == y.p && x.plane == y.plane && (x.plane == nullptr || x.axis == y.axis);
  }
  const detail::HomogeneousKernel::Point_3& exact() const {
    if (!exact_) exact_ = detail::plane_point<detail::HomogeneousKernel>(plane, axis, Vec3(p.x(), p.y(), p.z()));
    return *exact_;
  }
};

PatchPoint patch_point(const Point& p, const detail::Triangle3* plane, int axis) {
  PatchPoint q{p, plane, axis, detail::IntervalKernel::Point_3(p.x(), p.y(), p.z()), {}};
  if (plane != nullptr) {
    CGAL::Protect_FPU_rounding<true> upward;
    q.box = detail::plane_point<detail::IntervalKernel>(plane, axis, Vec3(p.x(), p.y(), p.z()));
  }
  return q;
}

/// The same predicates on points exactly on patches, each decided on its own: intervals, then
/// exact arithmetic (on the doubles when every point is one, else on homogeneous points). Callers
/// hold the rounding mode upward (CGAL::Protect_FPU_rounding<true>) for the intervals.
struct PatchOps {
  using P = PatchPoint;
  using Tri = std::array<PatchPoint, 3>;
  using DoubleExact = CGAL::Simple_cartesian<CGAL::Mpzf>;
  static DoubleExact::Point_3 exact_double(const Point& p) {
    return {CGAL::Mpzf(p.x()), CGAL::Mpzf(p.y()), CGAL::Mpzf(p.z())};
  }
  static CGAL::Orientation orient(const P& a, const P& b, const P& c, const P& d) {
    const CGAL::Uncertain<CGAL::Orientation> o = CGAL::orientation(a.box, b.box, c.box, d.box);
    if (CGAL::is_certain(o)) return CGAL::get_certain(o);
    if (!a.plane && !b.plane && !c.plane && !d.plane)
      return CGAL::orientation(exact_double(a.p), exact_double(b.p), exact_double(c.p), exact_double(d.p));
    return CGAL::orientation(a.exact(), b.exact(), c.exact(), d.exact());
  }
  static bool collinear(const P& a, const P& b, const P& c) {
    // Collinear iff (b - a) x (c - a) = 0: certainly not when an interval component excludes 0.
    const auto n = CGAL::cross_product(b.box - a.box, c.box - a.box);
    for (int k = 0; k < 3; ++k)
      if (CGAL::is_certain(CGAL::is_zero(n[k])) && !CGAL::get_certain(CGAL::is_zero(n[k]))) return false;
    if (!a.plane && !b.plane && !c.plane)
      return CGAL::collinear(exact_double(a.p), exact_double(b.p), exact_double(c.p));
    return CGAL::collinear(a.exact(), b.exact(), c.exact());
  }
  static Vec3 approx(const P& p) { return Vec3(p.p.x(), p.p.y(), p.p.z()); }
};

template <class Ops>
bool line_meets(const typename Ops::P& a, const typename Ops::P& b, const typename Ops::Tri& t) {
  return detail::line_meets_triangle(a, b, t, &Ops::orient);
}

/// Indices (0, j, k) of a non-collinear vertex triple of a convex polygon (counter-clockwise
/// polygons give a counter-clockwise triple), or {-1, -1, -1} when all vertices are collinear.
/// The widest triple is chosen on rounded coordinates; only the collinearity test is exact.
template <class EK>
std::array<int, 3> plane_triple(std::span<const typename EK::P> poly) {
  const int n = static_cast<int>(poly.size());
  auto approx = [&](int i) { return EK::approx(poly[static_cast<std::size_t>(i)]); };
  int best_j = -1, best_k = -1;
  double best = -1.0;
  for (int j = 1; j < n; ++j)
    for (int k = j + 1; k < n; ++k) {
      const double w = (approx(j) - approx(0)).cross(approx(k) - approx(0)).squaredNorm();
      if (w > best && !EK::collinear(poly[0], poly[j], poly[k])) {
        best = w;
        best_j = j;
        best_k = k;
      }
    }
  if (best_j < 0) return {-1, -1, -1};
  return {0, best_j, best_k};
}
std::array<int, 3> plane_triple(std::span<const Point> poly) { return plane_triple<DoubleOps>(poly); }

/// Some point of `pts` lies strictly in front of the plane of the polygon `poly`.
template <class EK>
bool any_strictly_in_front(std::span<const typename EK::P> poly, std::span<const typename EK::P> pts) {
  const auto [i, j, k] = plane_triple<EK>(poly);
  if (i < 0) return false;
  for (const auto& p : pts)
    if (EK::orient(poly[i], poly[j], poly[k], p) == CGAL::POSITIVE) return true;
  return false;
}

template <class Ops>
using Facet = detail::ShaftFacet<Ops>;

/// Drops the vertices of `all` collinear with their neighbours (T-vertices of elements): the
/// hull is the same.
template <class EK>
std::vector<typename EK::P> drop_collinear(std::vector<typename EK::P> all) {
  if (all.size() <= 3) return all;
  std::vector<typename EK::P> out;
  const std::size_t n = all.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!EK::collinear(all[(i + n - 1) % n], all[i], all[(i + 1) % n])) out.push_back(all[i]);
  return out.size() >= 3 ? out : all;
}

/// The polygon's vertices without T-vertices (drop_collinear()).
std::vector<Point> corners(std::span<const Vec3> poly) {
  std::vector<Point> all;
  all.reserve(poly.size());
  for (const Vec3& v : poly) all.push_back(to_point(v));
  return drop_collinear<DoubleOps>(std::move(all));
}

/// Box of some points (exact: the coordinates are the input doubles).
CGAL::Bbox_3 bbox_of(std::span<const Point> pts) {
  CGAL::Bbox_3 box = pts.front().bbox();
  for (const Point& p : pts) box += p.bbox();
  return box;
}

/// Classes of exactly coplanar triangles (twins of a zero-thickness wall, the triangles of one
/// planar patch or of coplanar patches): equal ids only for exactly coplanar triangles, decided by
/// exact predicates; triangles are bucketed by their rounded unit plane first, so a coplanar pair
/// on either side of a rounding boundary may get two ids (callers only lose a shortcut then).
std::vector<int> plane_classes(const std::vector<Triangle>& triangles, double magnitude) {
  std::map<std::array<long long, 4>, std::vector<int>> buckets;  // key -> representatives
  std::vector<int> id(triangles.size(), -1);
  std::vector<int> representative;  // class id -> triangle
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& tri = triangles[t];
    const Vec3 p0(tri[0].x(), tri[0].y(), tri[0].z());
    Vec3 n = (Vec3(tri[1].x(), tri[1].y(), tri[1].z()) - p0).cross(Vec3(tri[2].x(), tri[2].y(), tri[2].z()) - p0);
    n.normalize();
    int big = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(n[k]) > std::abs(n[big])) big = k;
    if (n[big] < 0) n = -n;
    const double q = 0x1p24;
    const std::array<long long, 4> key{std::llround(n.x() * q), std::llround(n.y() * q), std::llround(n.z() * q),
                                       std::llround(n.dot(p0) / magnitude * q)};
    std::vector<int>& reps = buckets[key];
    for (int c : reps) {
      const Triangle& r = triangles[static_cast<std::size_t>(representative[static_cast<std::size_t>(c)])];
      if (CGAL::orientation(r[0], r[1], r[2], tri[0]) == CGAL::COPLANAR &&
          CGAL::orientation(r[0], r[1], r[2], tri[1]) == CGAL::COPLANAR &&
          CGAL::orientation(r[0], r[1], r[2], tri[2]) == CGAL::COPLANAR) {
        id[t] = c;
        break;
      }
    }
    if (id[t] < 0) {
      id[t] = static_cast<int>(representative.size());
      representative.push_back(static_cast<int>(t));
      reps.push_back(id[t]);
    }
  }
  return id;
}

class CgalVisibility final : public Visibility {
 public:
  CgalVisibility(const Scene& scene, const VisibilityOptions& options);

  bool segment_blocked(const Vec3& a, int patch_a, const Vec3& b, int patch_b) const override {
    counters().segment_queries.add();
    return blocked(to_point(a), patch_a, to_point(b), patch_b);
  }

  Sight sight(const Vec3& a, int patch_a, const Vec3& b, int patch_b) const override;

  Sight sight_among(const Vec3& a, int patch_a, const Vec3& b, int patch_b,
                    std::span<const int> occluders) const override;

  PairClass classify(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b) const override {
    return classify_among(a, patch_a, b, patch_b, nullptr, nullptr);
  }

  PairClass classify_among(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b,
                           const std::vector<int>* candidates, std::vector<int>* occluders) const override {
    // Elements are parts of their patches, but their vertices are rounded off the patches'
    // planes: decide facing on the patches' own vertices first (a zero-thickness wall's inside
    // and outside elements must never face each other, however their midpoints rounded).
    PairClass c = PairClass::kFacingAway;
    if (occluders != nullptr) occluders->clear();
    if (patch_a < 0 || patch_b < 0 || patches_face(patch_a, patch_b))
      c = on_surface(a, patch_a) && on_surface(b, patch_b)
              ? classify_corners(corners(a), patch_a, corners(b), patch_b, true, candidates, occluders)
              : classify_on_patches(a, patch_a, b, patch_b, candidates, occluders);
    count(c);
    return c;
  }

  bool segment_blocked_among(const Vec3& a, int patch_a, const Vec3& b, int patch_b,
                             std::span<const int> occluders) const override {
    counters().segment_queries.add();
    return blocked(to_point(a), patch_a, to_point(b), patch_b, &occluders);
  }

  VisibilityEstimate estimate(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b, int samples,
                              std::uint64_t seed) const override;

  VisibilityEstimate estimate_from_point(const Vec3& x, int patch_x, std::span<const Vec3> b, int patch_b, int samples,
                                         std::uint64_t seed) const override;

  RayHit first_hit(const Vec3& x, int patch, const Vec3& direction) const override;

  bool scene_has_occlusion() const override {
    std::call_once(occlusion_once_, [this] { occlusion_ = decide_occlusion(); });
    return occlusion_;
  }

 private:
  /// A segment end on a patch (see end_on()).
  struct PatchEnd {
    detail::SegmentEnd end;  ///< plane null: the double point is exactly on its patch's surface
    int triangle = -1;       ///< the fan triangle (index into triangles_) the point lies on
    bool on_patch = true;    ///< false: x's shadow along the patch's axis misses the patch
  };
  /// The point of patch `patch`'s surface (its fan triangles) that x stands for: the one with x's
  /// coordinates on the two axes across the patch's dominant normal axis, which is x itself when
  /// x lies exactly on the surface. For patch < 0, x.
  PatchEnd end_on(const Point& x, int patch) const;
  /// Some vertex of each patch lies strictly in front of the other's plane (exact; false for
  /// coplanar patches, found by their plane class without arithmetic).
  bool patches_face(int pa, int pb) const;
  /// Whether a patch other than patch_a and patch_b blocks the open segment between the points the
  /// ends stand for; only the patches in `*occluders` when it is not null.
  bool blocked(const Point& a, int patch_a, const Point& b, int patch_b,
               const std::span<const int>* occluders = nullptr) const;
  bool blocked_between(const Point& a, int patch_a, const Point& b, int patch_b,
                       const std::span<const int>* occluders) const;
  bool blocked_between(const PatchEnd& a, int patch_a, const PatchEnd& b, int patch_b,
                       const std::span<const int>* occluders) const;
  /// The same with the ends' segment already built.
  bool blocked_between(const detail::OnPatchSegment& segment, const PatchEnd& a, int patch_a, const PatchEnd& b,
                       int patch_b, const std::span<const int>* occluders) const;
  Sight sight_of(const Vec3& a, int patch_a, const Vec3& b, int patch_b, const std::span<const int>* occluders) const;
  /// A triangle of triangles_ with its coordinates and plane class.
  struct TriangleRef {
    const Triangle& triangle;
    const detail::Triangle3& coords;
    int plane;
  };
  TriangleRef triangle_ref(std::size_t i) const { return {triangles_[i], triangle_coords_[i], triangle_plane_[i]}; }
  /// Whether meets(TriangleRef) holds for a triangle of a patch other than patch_a and patch_b
  /// whose box the segment a-b may meet; only `*occluders`' triangles when not null.
  template <class Meets>
  bool any_triangle_meets(const Point& a, int patch_a, const Point& b, int patch_b,
                          const std::span<const int>* occluders, const Meets& meets) const;
  PairClass classify_corners(std::span<const Point> a, int patch_a, std::span<const Point> b, int patch_b,
                             bool ends_on_patches = false, const std::vector<int>* candidates = nullptr,
                             std::vector<int>* occluders = nullptr) const;
  /// classify_among() of two elements whose vertices are not all exactly on their patches' surfaces.
  PairClass classify_on_patches(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b,
                                const std::vector<int>* candidates, std::vector<int>* occluders) const;
  /// The shaft classification on points with the predicates of Ops (DoubleOps or PatchOps);
  /// `box` holds them all; `ends_on_patches`: both polygons lie exactly in their patches' planes.
  /// Candidates and occluders as in classify_among().
  template <class Ops>
  PairClass classify_points(std::span<const typename Ops::P> a, int patch_a, std::span<const typename Ops::P> b,
                            int patch_b, const CGAL::Bbox_3& box, bool ends_on_patches,
                            const std::vector<int>* candidates, std::vector<int>* occluders) const;
  /// True when every vertex of `poly` lies exactly on patch `patch`'s surface (or patch < 0).
  bool on_surface(std::span<const Vec3> poly, int patch) const;
  template <class Ops>
  bool patch_hides(int patch, std::span<const typename Ops::P> a, std::span<const typename Ops::P> b) const;
  /// Triangle i of triangles_ as Ops's triangle.
  template <class Ops>
  typename Ops::Tri triangle_as(std::size_t i) const {
    if constexpr (std::is_same_v<Ops, DoubleOps>) {
      return triangles_[i];
    } else {
      const Triangle& t = triangles_[i];
      return {patch_point(t[0], nullptr, 0), patch_point(t[1], nullptr, 0), patch_point(t[2], nullptr, 0)};
    }
  }
  bool decide_occlusion() const;
  int patch_of(TriangleIterator it) const { return triangle_patch_[it - triangles_.begin()]; }
  void count(PairClass c) const {
    VisibilityCounters& k = counters();
    k.pair_queries.add();
    switch (c) {
      case PairClass::kFacingAway:
        k.pairs_facing_away.add();
        break;
      case PairClass::kFullyVisible:
        k.pairs_visible.add();
        break;
      case PairClass::kFullyHidden:
        k.pairs_hidden.add();
        break;
      case PairClass::kPartial:
        k.pairs_partial.add();
        break;
    }
  }

  std::vector<Triangle> triangles_;  ///< non-degenerate fan triangles of all patches
  std::vector<int> triangle_patch_;
  std::vector<CGAL::Bbox_3> triangle_boxes_;
  std::vector<CGAL::Bbox_3> patch_boxes_;             ///< the union of each patch's triangle_boxes_
  std::vector<std::pair<int, int>> patch_triangles_;  ///< [begin, end) into triangles_ per patch
  std::vector<detail::Triangle3> triangle_coords_;    ///< triangles_ as doubles
  std::vector<int> triangle_plane_;                   ///< plane_classes() of triangles_
  std::vector<std::vector<Point>> patch_points_;      ///< each patch's vertices
  /// The axis of a patch's largest normal component and the patch's coordinate on that axis when
  /// constant (else NaN).
  struct PatchFrame {
    int axis = 0;
    double level = 0.0;
  };
  std::vector<PatchFrame> patch_frame_;
  /// Each fan triangle's shadow along its patch's axis and that shadow's orientation (COLLINEAR
  /// when the triangle is seen edge-on along the axis, only in a non-planar patch): end_on() finds
  /// the triangle under a point by three exact 2D orientations each, on compact data.
  struct FanShadow {
    std::array<K::Point_2, 3> p;
    CGAL::Orientation orientation = CGAL::COLLINEAR;
  };
  std::vector<FanShadow> fan_shadow_;
  /// A patch of two fan triangles whose shadow along its axis is a rectangle with sides along the
  /// other two axes (a wall, floor or box face of an axis-aligned room): end_on() tests x's shadow
  /// against the rectangle's bounds and the one diagonal, exactly as the triangles' six
  /// orientations would decide.
  struct RectangleShadow {
    bool is = false;
    double lo_i = 0.0, hi_i = 0.0, lo_j = 0.0, hi_j = 0.0;
  };
  std::vector<RectangleShadow> rectangle_shadow_;
  std::vector<char> patch_planar_;  ///< all vertices exactly coplanar
  std::vector<Point> vertices_;     ///< every patch vertex, for the convex-hull test
  double magnitude_ = 0.0;          ///< largest |coordinate| of the scene
  Tree tree_;
  VisibilityOptions options_;
  detail::SegmentBvh bvh_;               ///< segment queries (unless options_ ask for tree_)
  std::vector<Triangle> bvh_triangles_;  ///< triangles_ in the hierarchy's leaf order (locality)
  std::vector<detail::Triangle3> bvh_triangle_coords_;
  std::vector<int> bvh_plane_;
  std::vector<int> bvh_patch_;
  std::vector<Vec3> patch_normal_;  ///< each patch's unit front normal (first_hit())
  mutable std::once_flag occlusion_once_;
  mutable bool occlusion_ = true;
};

CgalVisibility::CgalVisibility(const Scene& scene, const VisibilityOptions& options) : options_(options) {
  patch_triangles_.reserve(scene.patches.size());
  for (const Patch& patch : scene.patches) patch_normal_.push_back(patch.normal);
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
      for (const Point& x : pts)
        planar = planar && CGAL::orientation(pts[tri[0]], pts[tri[1]], pts[tri[2]], x) == CGAL::COPLANAR;
    patch_triangles_.emplace_back(begin, static_cast<int>(triangles_.size()));
    CGAL::Bbox_3 box;  // empty
    for (std::size_t t = static_cast<std::size_t>(begin); t < triangles_.size(); ++t) box += triangle_boxes_[t];
    patch_boxes_.push_back(box);
    patch_planar_.push_back(planar ? 1 : 0);
    patch_points_.push_back(pts);
    const Vec3 n = newell_normal(v);
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(n[k]) > std::abs(n[axis])) axis = k;
    const bool level = std::all_of(v.begin(), v.end(), [&](const Vec3& x) { return x[axis] == v[0][axis]; });
    patch_frame_.push_back({axis, level ? v[0][axis] : std::numeric_limits<double>::quiet_NaN()});
  }
  for (std::size_t p = 0; p < patch_triangles_.size(); ++p) {
    const int k = patch_frame_[p].axis, i = (k + 1) % 3, j = (k + 2) % 3;
    for (int t = patch_triangles_[p].first; t < patch_triangles_[p].second; ++t) {
      const Triangle& tri = triangles_[static_cast<std::size_t>(t)];
      FanShadow f;
      for (int m = 0; m < 3; ++m) f.p[static_cast<std::size_t>(m)] = K::Point_2(tri[m][i], tri[m][j]);
      f.orientation = CGAL::orientation(f.p[0], f.p[1], f.p[2]);
      fan_shadow_.push_back(f);
    }
    RectangleShadow r;
    const auto& pts = patch_points_[p];
    if (patch_triangles_[p].second - patch_triangles_[p].first == 2 && pts.size() == 4) {
      const FanShadow& a = fan_shadow_[static_cast<std::size_t>(patch_triangles_[p].first)];
      const FanShadow& b = fan_shadow_[static_cast<std::size_t>(patch_triangles_[p].first + 1)];
      r.lo_i = std::min({pts[0][i], pts[1][i], pts[2][i], pts[3][i]});
      r.hi_i = std::max({pts[0][i], pts[1][i], pts[2][i], pts[3][i]});
      r.lo_j = std::min({pts[0][j], pts[1][j], pts[2][j], pts[3][j]});
      r.hi_j = std::max({pts[0][j], pts[1][j], pts[2][j], pts[3][j]});
      // Each corner of the bounds is a vertex (the shadow is that rectangle), and the fan is the
      // two triangles (0, 1, 2), (0, 2, 3) with the same orientation.
      int corners = 0;
      for (const double u : {r.lo_i, r.hi_i})
        for (const double w : {r.lo_j, r.hi_j})
          corners += std::any_of(pts.begin(), pts.end(), [&](const Point& x) { return x[i] == u && x[j] == w; });
      r.is = corners == 4 && r.lo_i < r.hi_i && r.lo_j < r.hi_j && a.orientation != CGAL::COLLINEAR &&
             a.orientation == b.orientation && a.p[0] == b.p[0] && a.p[2] == b.p[1];
    }
    rectangle_shadow_.push_back(r);
  }
  for (const Triangle& t : triangles_) {
    detail::Triangle3 c;
    for (int k = 0; k < 3; ++k) c[k] = Vec3(t[k].x(), t[k].y(), t[k].z());
    triangle_coords_.push_back(c);
  }
  triangle_plane_ = plane_classes(triangles_, magnitude_ > 0.0 ? magnitude_ : 1.0);
  tree_.rebuild(triangles_.cbegin(), triangles_.cend());
  std::vector<detail::Box3> boxes(triangles_.size());
  for (std::size_t i = 0; i < triangles_.size(); ++i)
    for (int k = 0; k < 3; ++k) boxes[i].lo[k] = triangle_boxes_[i].min(k), boxes[i].hi[k] = triangle_boxes_[i].max(k);
  bvh_ = detail::SegmentBvh(boxes);
  for (std::uint32_t i : bvh_.order()) {
    bvh_triangles_.push_back(triangles_[i]);
    bvh_triangle_coords_.push_back(triangle_coords_[i]);
    bvh_plane_.push_back(triangle_plane_[i]);
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

// Traversal that stops at the first triangle for which `meets(index into triangles_)` holds.
template <class Meets>
class BlockingTraversal {
 public:
  BlockingTraversal(const std::vector<Triangle>& triangles, const std::vector<int>& patch_of,
                    const std::vector<CGAL::Bbox_3>& boxes, const SegmentBoxCull& cull, int patch_a, int patch_b,
                    const Meets& meets)
      : triangles_(triangles),
        patch_of_(patch_of),
        boxes_(boxes),
        cull_(cull),
        pa_(patch_a),
        pb_(patch_b),
        meets_(meets) {}
  bool go_further() const { return !blocked_; }
  void intersection(const Segment&, const Primitive& primitive) {
    // CGAL's tree hands over the primitives of a two-primitive node without testing their boxes.
    const std::size_t index = static_cast<std::size_t>(primitive.id() - triangles_.begin());
    const int patch = patch_of_[index];
    if (patch == pa_ || patch == pb_ || !cull_.may_meet(boxes_[index])) return;
    if (meets_(index)) blocked_ = true;
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
  const SegmentBoxCull& cull_;
  int pa_, pb_;
  const Meets& meets_;
  bool blocked_ = false;
};

CgalVisibility::PatchEnd CgalVisibility::end_on(const Point& x, int patch) const {
  PatchEnd e;
  e.end.x = Vec3(x.x(), x.y(), x.z());
  if (patch < 0) return e;
  const auto [begin, end] = patch_triangles_[static_cast<std::size_t>(patch)];
  const PatchFrame& frame = patch_frame_[static_cast<std::size_t>(patch)];
  const int k = frame.axis, i = (k + 1) % 3, j = (k + 2) % 3;
  e.end.axis = k;
  // The fan triangle whose shadow along axis k holds x's (exact: dropping a coordinate is exact).
  const K::Point_2 q(x[i], x[j]);
  int fallback = -1;
  const RectangleShadow& rectangle = rectangle_shadow_[static_cast<std::size_t>(patch)];
  if (rectangle.is) {
    // Inside the rectangle, the first triangle (0, 1, 2) holds q unless q lies strictly across the
    // diagonal 0-2 from vertex 1: its other two edges are sides of the rectangle.
    fallback = begin;
    if (x[i] >= rectangle.lo_i && x[i] <= rectangle.hi_i && x[j] >= rectangle.lo_j && x[j] <= rectangle.hi_j) {
      const FanShadow& f = fan_shadow_[static_cast<std::size_t>(begin)];
      e.triangle = CGAL::orientation(f.p[0], f.p[2], q) != f.orientation ? begin : begin + 1;
    }
  }
  for (int t = rectangle.is ? end : begin; t < end && e.triangle < 0; ++t) {
    const FanShadow& f = fan_shadow_[static_cast<std::size_t>(t)];
    if (f.orientation == CGAL::COLLINEAR) continue;  // seen edge-on along k
    if (fallback < 0) fallback = t;
    bool inside = true;
    for (std::size_t m = 0; m < 3 && inside; ++m)
      inside = CGAL::orientation(f.p[m], f.p[(m + 1) % 3], q) != -f.orientation;
    if (inside) e.triangle = t;
  }
  if (e.triangle < 0) {
    e.on_patch = false;
    e.triangle = fallback;
    if (fallback < 0) return e;  // no triangle to project onto: x as it is
  }
  // On an axis-aligned patch a double point is on the surface when its coordinate is the patch's;
  // elsewhere it almost never is, and projecting a point that is gives the point itself.
  if (std::isnan(frame.level) || x[k] != frame.level)
    e.end.plane = &triangle_coords_[static_cast<std::size_t>(e.triangle)];
  return e;
}

bool CgalVisibility::on_surface(std::span<const Vec3> poly, int patch) const {
  if (patch < 0) return true;
  const PatchFrame& frame = patch_frame_[static_cast<std::size_t>(patch)];
  if (std::isnan(frame.level)) {
    // Not axis-aligned: only the patch's own vertices are known to lie on it without arithmetic.
    const auto& own = patch_points_[static_cast<std::size_t>(patch)];
    return std::all_of(poly.begin(), poly.end(),
                       [&](const Vec3& v) { return std::find(own.begin(), own.end(), to_point(v)) != own.end(); });
  }
  return std::all_of(poly.begin(), poly.end(), [&](const Vec3& v) { return v[frame.axis] == frame.level; });
}

bool CgalVisibility::patches_face(int pa, int pb) const {
  const auto [ba, ea] = patch_triangles_[static_cast<std::size_t>(pa)];
  const auto [bb, eb] = patch_triangles_[static_cast<std::size_t>(pb)];
  if (ba == ea || bb == eb) return false;  // no area
  const bool planar = patch_planar_[static_cast<std::size_t>(pa)] && patch_planar_[static_cast<std::size_t>(pb)];
  if (planar && triangle_plane_[static_cast<std::size_t>(ba)] == triangle_plane_[static_cast<std::size_t>(bb)])
    return false;
  // In front of the plane of any of the patch's fan triangles (one plane unless the patch is a
  // quad bent within the reader's planarity tolerance).
  const auto in_front = [&](int plane_of, int points_of) {
    const auto [begin, end] = patch_triangles_[static_cast<std::size_t>(plane_of)];
    for (int i = begin; i < end; ++i) {
      const Triangle& t = triangles_[static_cast<std::size_t>(i)];
      for (const Point& p : patch_points_[static_cast<std::size_t>(points_of)])
        if (p != t[0] && p != t[1] && p != t[2] && CGAL::orientation(t[0], t[1], t[2], p) == CGAL::POSITIVE)
          return true;
    }
    return false;
  };
  return in_front(pa, pb) && in_front(pb, pa);
}

bool CgalVisibility::blocked(const Point& a, int patch_a, const Point& b, int patch_b,
                             const std::span<const int>* occluders) const {
  if (triangles_.empty()) return false;
  const PatchEnd ea = end_on(a, patch_a), eb = end_on(b, patch_b);
  if (ea.end.plane == nullptr && eb.end.plane == nullptr) return blocked_between(a, patch_a, b, patch_b, occluders);
  return blocked_between(ea, patch_a, eb, patch_b, occluders);
}

template <class Meets>
bool CgalVisibility::any_triangle_meets(const Point& a, int patch_a, const Point& b, int patch_b,
                                        const std::span<const int>* occluders, const Meets& meets) const {
  if (occluders != nullptr) {
    const SegmentBoxCull cull(a, b, magnitude_);
    const auto patch_meets = [&](int patch) {
      if (patch == patch_a || patch == patch_b || !cull.may_meet(patch_boxes_[static_cast<std::size_t>(patch)]))
        return false;
      const auto [begin, end] = patch_triangles_[static_cast<std::size_t>(patch)];
      if (end - begin == 1) return meets(triangle_ref(static_cast<std::size_t>(begin)));
      for (int i = begin; i < end; ++i)
        if (cull.may_meet(triangle_boxes_[static_cast<std::size_t>(i)]) &&
            meets(triangle_ref(static_cast<std::size_t>(i))))
          return true;
      return false;
    };
    // A pair's rays come one after another with the same list, and the occluder that blocked one
    // ray often blocks the next (the shadow cache of Haines & Greenberg 1986): it is tested first.
    // Whether a ray is blocked does not depend on the order.
    thread_local const int* cached_list = nullptr;
    thread_local std::size_t cached = 0;
    const std::span<const int> list = *occluders;
    const bool hit = list.data() == cached_list && cached < list.size();
    if (hit && patch_meets(list[cached])) return true;
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (hit && k == cached) continue;
      if (patch_meets(list[k])) {
        cached_list = list.data();
        cached = k;
        return true;
      }
    }
    return false;
  }
  if (!options_.cgal_tree_for_segments) {
    const detail::SegmentCull cull({a.x(), a.y(), a.z()}, {b.x(), b.y(), b.z()}, magnitude_);
    return bvh_.any_hit(cull, [&](std::uint32_t i) {
      const int patch = bvh_patch_[i];
      return patch != patch_a && patch != patch_b &&
             meets(TriangleRef{bvh_triangles_[i], bvh_triangle_coords_[i], bvh_plane_[i]});
    });
  }
  const SegmentBoxCull cull(a, b, magnitude_);
  const auto meets_index = [&](std::size_t i) { return meets(triangle_ref(i)); };
  BlockingTraversal traversal(triangles_, triangle_patch_, triangle_boxes_, cull, patch_a, patch_b, meets_index);
  tree_.traversal(Segment(a, b), traversal);
  return traversal.blocked();
}

RayHit CgalVisibility::first_hit(const Vec3& x, int patch, const Vec3& direction) const {
  counters().segment_queries.add();
  // A segment long enough to leave the scene's bounding cube [-m, m]^3 from any point in it.
  const double m =
      std::max({magnitude_, std::abs(x.x()), std::abs(x.y()), std::abs(x.z()), std::numeric_limits<double>::min()});
  const Vec3 d = direction * (4.0 * m);
  const Vec3 end = x + d;
  const detail::SegmentCull cull({x.x(), x.y(), x.z()}, {end.x(), end.y(), end.z()}, magnitude_);
  constexpr double kEdge = 1e-12, kNear = 1e-12;
  double nearest = INFINITY;
  RayHit hit;
  bvh_.any_hit(cull, [&](std::uint32_t i) {
    if (bvh_patch_[i] == patch) return false;
    // Moller & Trumbore 1997, "Fast, minimum storage ray-triangle intersection"; t in units of d.
    const detail::Triangle3& t = bvh_triangle_coords_[i];
    const Vec3 e1 = t[1] - t[0], e2 = t[2] - t[0];
    const Vec3 p = d.cross(e2);
    const double det = e1.dot(p);
    if (det == 0.0) return false;  // the ray runs in the triangle's plane
    const double inv = 1.0 / det;
    const Vec3 s0 = x - t[0];
    const double u = s0.dot(p) * inv;
    if (u < -kEdge || u > 1.0 + kEdge) return false;
    const Vec3 q = s0.cross(e1);
    const double v = d.dot(q) * inv;
    if (v < -kEdge || u + v > 1.0 + kEdge) return false;
    const double along = e2.dot(q) * inv;
    if (!(along > kNear) || along > nearest + kNear) return false;
    // Of patches met at one distance (a zero-thickness wall's two sides) the front counts.
    const bool front = direction.dot(patch_normal_[static_cast<std::size_t>(bvh_patch_[i])]) < 0.0;
    if (along < nearest - kNear || (front && !hit.front)) {
      nearest = std::min(nearest, along);
      hit = {bvh_patch_[i], front};
    }
    return false;
  });
  return hit;
}

bool CgalVisibility::blocked_between(const Point& a, int patch_a, const Point& b, int patch_b,
                                     const std::span<const int>* occluders) const {
  if (a == b) return false;  // the open segment is empty
  return any_triangle_meets(a, patch_a, b, patch_b, occluders,
                            [&](const TriangleRef& t) { return open_segment_meets_triangle(a, b, t.triangle); });
}

bool CgalVisibility::blocked_between(const PatchEnd& ea, int patch_a, const PatchEnd& eb, int patch_b,
                                     const std::span<const int>* occluders) const {
  return blocked_between(detail::OnPatchSegment(ea.end, eb.end), ea, patch_a, eb, patch_b, occluders);
}

bool CgalVisibility::blocked_between(const detail::OnPatchSegment& segment, const PatchEnd& ea, int patch_a,
                                     const PatchEnd& eb, int patch_b, const std::span<const int>* occluders) const {
  if (segment.degenerate()) return false;
  // The ends' points lie within a few units in the last place of the doubles, far inside the
  // culling tests' padding (2^-40 of the coordinates' magnitude).
  // An end lies exactly in the plane of its triangle, so in that of every triangle coplanar with it.
  const int plane_a = ea.triangle >= 0 ? triangle_plane_[static_cast<std::size_t>(ea.triangle)] : -1;
  const int plane_b = eb.triangle >= 0 ? triangle_plane_[static_cast<std::size_t>(eb.triangle)] : -1;
  return any_triangle_meets(
      to_point(ea.end.x), patch_a, to_point(eb.end.x), patch_b, occluders,
      [&](const TriangleRef& t) { return segment.meets(t.coords, t.plane == plane_a, t.plane == plane_b); });
}

Sight CgalVisibility::sight(const Vec3& a, int patch_a, const Vec3& b, int patch_b) const {
  return sight_of(a, patch_a, b, patch_b, nullptr);
}

Sight CgalVisibility::sight_among(const Vec3& a, int patch_a, const Vec3& b, int patch_b,
                                  std::span<const int> occluders) const {
  return sight_of(a, patch_a, b, patch_b, &occluders);
}

Sight CgalVisibility::sight_of(const Vec3& a, int patch_a, const Vec3& b, int patch_b,
                               const std::span<const int>* occluders) const {
  counters().segment_queries.add();
  const Point pa = to_point(a), pb = to_point(b);
  const PatchEnd ea = end_on(pa, patch_a), eb = end_on(pb, patch_b);
  if (patch_a < 0 || patch_b < 0 || !ea.on_patch || !eb.on_patch || ea.triangle < 0 || eb.triangle < 0)
    return Sight::kFacingAway;
  const Triangle& ta = triangles_[static_cast<std::size_t>(ea.triangle)];
  const Triangle& tb = triangles_[static_cast<std::size_t>(eb.triangle)];
  if (ea.end.plane == nullptr && eb.end.plane == nullptr) {
    if (CGAL::orientation(ta[0], ta[1], ta[2], pb) != CGAL::POSITIVE ||
        CGAL::orientation(tb[0], tb[1], tb[2], pa) != CGAL::POSITIVE)
      return Sight::kFacingAway;
    return blocked_between(pa, patch_a, pb, patch_b, occluders) ? Sight::kBlocked : Sight::kVisible;
  }
  const detail::OnPatchSegment segment(ea.end, eb.end);
  if (!segment.facing(triangle_coords_[static_cast<std::size_t>(ea.triangle)],
                      triangle_coords_[static_cast<std::size_t>(eb.triangle)]))
    return Sight::kFacingAway;
  return blocked_between(segment, ea, patch_a, eb, patch_b, occluders) ? Sight::kBlocked : Sight::kVisible;
}

// The shaft's bounding planes in doubles, for culling boxes before any exact test (Haines &
// Wallace 1994, shaft culling): a box all of whose points lie on the outer side of one plane, by
// more than a slack many orders above the rounding of the plane's arithmetic, cannot meet the
// shaft. The shaft's box alone lets a long diagonal shaft (across a city) visit most of the scene.
// A point that stands for a point on its patch (PatchOps) is off its double coordinates by a few
// units in the last place, far inside the slack.
class ShaftPlanes {
 public:
  template <class Ops>
  ShaftPlanes(std::span<const Facet<Ops>> facets, double scene_magnitude) : magnitude_(scene_magnitude) {
    for (const Facet<Ops>& f : facets) {
      const Vec3 p = Ops::approx(f.p);
      const Vec3 u = Ops::approx(f.q) - p, v = Ops::approx(f.r) - p;
      const Vec3 n = u.cross(v);  // CGAL::orientation(p, q, r, x) is the sign of n . (x - p)
      planes_.push_back({n, n.dot(p), slack(u, v)});
    }
  }
  /// The slack of the plane spanned by edges u and v: |n . (x - p)| <= |u| |v| |x - p| with
  /// |x - p| <= 2 (scene magnitude) for x in the scene; the slack is 2^-30 of that bound, the
  /// arithmetic's error a few 2^-52.
  double slack(const Vec3& u, const Vec3& v) const {
    return std::ldexp(u.cwiseAbs().sum() * v.cwiseAbs().sum() * 4.0 * magnitude_, -30) +
           std::numeric_limits<double>::min();
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
  /// The side of x of facet plane k where the double arithmetic settles it beyond the slack
  /// (+1 or -1), else 0: then only the exact predicate can tell.
  int sign(std::size_t k, const Vec3& x) const {
    const Plane& pl = planes_[k];
    const double s = pl.normal.dot(x) - pl.offset;
    return s > pl.slack ? 1 : s < -pl.slack ? -1 : 0;
  }

 private:
  struct Plane {
    Vec3 normal;
    double offset, slack;
  };
  std::vector<Plane> planes_;
  double magnitude_;
};

// Decides, triangle by triangle, which patches may meet the shaft's interior and records them in
// `hits`: the test of the top of this file, for the tree traversal and for candidate lists alike.
// Ops gives the shaft's points and predicates:
// DoubleOps for double points, PatchOps for elements whose vertices stand for points on their
// patches; the exact contact step (probes, rational clipping) runs only on double points, and
// without it a contact counts as a hit (partial), which is conservative.
template <class Ops, class TriangleOf>
class ShaftTest {
 public:
  ShaftTest(const std::vector<Triangle>& triangles, const TriangleOf& triangle_of, const std::vector<int>& patch_of,
            const std::vector<int>& plane_of, std::array<int, 2> end_planes, std::span<const Facet<Ops>> facets,
            const ShaftPlanes& planes, std::span<const typename Ops::P> shaft_points,
            std::span<const std::pair<Point, Point>> probes, bool exact_contacts, int patch_a, int patch_b,
            std::vector<int>* hits)
      : triangles_(triangles),
        triangle_of_(triangle_of),
        patch_of_(patch_of),
        plane_of_(plane_of),
        end_planes_(end_planes),
        facets_(facets),
        planes_(planes),
        pts_(shaft_points),
        probes_(probes),
        exact_contacts_(exact_contacts),
        pa_(patch_a),
        pb_(patch_b),
        hits_(hits) {
    for (const auto& p : pts_) approx_.push_back(Ops::approx(p));
  }
  void operator()(std::size_t index) {
    const int patch = patch_of_[index];
    if (patch == pa_ || patch == pb_) return;
    // A triangle in the plane of an end's patch lies in a bounding plane of the shaft (the end
    // polygons lie exactly in their patches' planes): it cannot meet the interior.
    if (plane_of_[index] == end_planes_[0] || plane_of_[index] == end_planes_[1]) return;
    if (!hits_->empty() && hits_->back() == patch) return;  // the patch's other triangle: already a hit
    const typename Ops::Tri t = triangle_of_(index);
    const std::array<Vec3, 3> tv{Ops::approx(t[0]), Ops::approx(t[1]), Ops::approx(t[2])};
    for (std::size_t f = 0; f < facets_.size(); ++f)
      if (side(f, t[0], tv[0]) != CGAL::POSITIVE && side(f, t[1], tv[1]) != CGAL::POSITIVE &&
          side(f, t[2], tv[2]) != CGAL::POSITIVE)
        return;                     // a facet plane weakly separates t from the shaft
    if (!straddles(t, tv)) return;  // t's plane weakly separates the shaft from t
    if constexpr (std::is_same_v<Ops, DoubleOps>) {
      bool inside = true;
      for (std::size_t f = 0; f < facets_.size() && inside; ++f)
        for (int k = 0; k < 3 && inside; ++k) inside = side(f, t[k], tv[k]) == CGAL::POSITIVE;
      if (!inside && exact_contacts_ && !probe_segment_hits(t) && !clipped_probe_hits(t) && !meets_interior_exactly(t))
        return;  // touches only
    }
    hits_->push_back(patch);
  }

 private:
  /// Facet f's side of x (approximated by xv): the double plane where its slack settles it, the
  /// exact predicate where it cannot. Both give the same answer wherever the first answers.
  CGAL::Orientation side(std::size_t f, const typename Ops::P& x, const Vec3& xv) const {
    const int s = planes_.sign(f, xv);
    return s != 0 ? static_cast<CGAL::Orientation>(s) : facets_[f].side(x);
  }
  /// True iff the shaft's points lie strictly on both sides of t's plane; as side(), the double
  /// plane first, the exact orientation only for points within its slack.
  bool straddles(const typename Ops::Tri& t, const std::array<Vec3, 3>& tv) const {
    const Vec3 u = tv[1] - tv[0], v = tv[2] - tv[0];
    const Vec3 n = u.cross(v);
    const double slack = planes_.slack(u, v);
    bool pos = false, neg = false;
    for (std::size_t i = 0; i < pts_.size() && !(pos && neg); ++i) {
      const double s = n.dot(approx_[i] - tv[0]);
      const CGAL::Orientation o = s > slack    ? CGAL::POSITIVE
                                  : s < -slack ? CGAL::NEGATIVE
                                               : Ops::orient(t[0], t[1], t[2], pts_[i]);
      pos |= o == CGAL::POSITIVE;
      neg |= o == CGAL::NEGATIVE;
    }
    return pos && neg;
  }
  /// Sufficient and exact: some probe segment whose ends lie strictly inside the shaft crosses t
  /// (its ends strictly on both sides of t's plane, the crossing in closed t), so t meets the
  /// interior. The probes are rounded points near the shaft's vertex pairs; a probe end that is
  /// not strictly inside (the exact facet test) is not used.
  bool probe_segment_hits(const Triangle& t) const {
    for (const auto& [u, v] : probes_)
      if (probe_hits(u, v, t)) return true;
    return false;
  }
  static bool probe_hits(const Point& u, const Point& v, const Triangle& t) {
    const CGAL::Orientation ou = CGAL::orientation(t[0], t[1], t[2], u);
    const CGAL::Orientation ov = CGAL::orientation(t[0], t[1], t[2], v);
    return ou != CGAL::COPLANAR && ov == CGAL::opposite(ou) && crossing_inside(u, v, t);
  }
  /// Sufficient and exact, for a triangle that crosses the shaft's boundary (the common contact:
  /// an occluder partly inside): t is clipped to the shaft in doubles, and a short probe segment
  /// through the mean c of the clipped polygon's vertices, along t's normal, a quarter of c's
  /// distance to the nearest shaft plane to either side, is tested exactly as the probes above.
  /// Rounding can only make it fail, never pass wrongly; then the rational clip decides.
  bool clipped_probe_hits(const Triangle& t) const {
    thread_local std::vector<Vec3> poly, out;
    poly.assign({to_vec(t[0]), to_vec(t[1]), to_vec(t[2])});
    for (const Facet<Ops>& f : facets_) {
      const Vec3 o = to_vec(f.p), n = (to_vec(f.q) - o).cross(to_vec(f.r) - o);  // orientation(p, q, r, x) > 0
      out.clear();
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3& x = poly[i];
        const Vec3& y = poly[(i + 1) % poly.size()];
        const double sx = n.dot(x - o), sy = n.dot(y - o);
        if (sx >= 0.0) out.push_back(x);
        if ((sx > 0.0 && sy < 0.0) || (sx < 0.0 && sy > 0.0)) out.push_back(x + (sx / (sx - sy)) * (y - x));
      }
      std::swap(poly, out);
      if (poly.size() < 3) return false;
    }
    Vec3 c = Vec3::Zero();
    for (const Vec3& x : poly) c += x;
    c /= double(poly.size());
    double reach = std::numeric_limits<double>::infinity();
    for (const Facet<Ops>& f : facets_) {
      const Vec3 o = to_vec(f.p), n = (to_vec(f.q) - o).cross(to_vec(f.r) - o);
      reach = std::min(reach, n.dot(c - o) / n.norm());
    }
    const Vec3 nt = (to_vec(t[1]) - to_vec(t[0])).cross(to_vec(t[2]) - to_vec(t[0])).normalized();
    if (!(reach > 0.0) || !nt.allFinite()) return false;
    const Point u = to_point(c + 0.25 * reach * nt), v = to_point(c - 0.25 * reach * nt);
    for (const Facet<Ops>& f : facets_)
      if (f.side(u) != CGAL::POSITIVE || f.side(v) != CGAL::POSITIVE) return false;
    return probe_hits(u, v, t);
  }
  static Vec3 to_vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }
  bool meets_interior_exactly(const Triangle& t) const {
    std::vector<std::array<Vec3, 3>> planes;
    for (const Facet<Ops>& f : facets_) planes.push_back({to_vec(f.p), to_vec(f.q), to_vec(f.r)});
    return detail::triangle_meets_interior({to_vec(t[0]), to_vec(t[1]), to_vec(t[2])}, planes);
  }

  const std::vector<Triangle>& triangles_;
  const TriangleOf& triangle_of_;
  const std::vector<int>& patch_of_;
  const std::vector<int>& plane_of_;
  std::array<int, 2> end_planes_;
  std::span<const Facet<Ops>> facets_;
  const ShaftPlanes& planes_;
  std::span<const typename Ops::P> pts_;
  std::vector<Vec3> approx_;  // pts_ in doubles
  std::span<const std::pair<Point, Point>> probes_;
  bool exact_contacts_;
  int pa_, pb_;
  std::vector<int>* hits_;
};

// Traversal that hands every triangle whose box overlaps the shaft's box to a ShaftTest.
template <class Test>
class ShaftTraversal {
 public:
  ShaftTraversal(const std::vector<Triangle>& triangles, const std::vector<CGAL::Bbox_3>& boxes,
                 const ShaftPlanes& planes, Test& test)
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
  Test& test_;
};

template <class Ops>
bool CgalVisibility::patch_hides(int patch, std::span<const typename Ops::P> a,
                                 std::span<const typename Ops::P> b) const {
  const auto [begin, end] = patch_triangles_[patch];
  const auto triangle = [&](int i) { return triangle_as<Ops>(static_cast<std::size_t>(i)); };
  // Every segment between a vertex of A and a vertex of B crosses the triangles [lo, hi), whose
  // union is convex and planar, strictly between its endpoints.
  auto separates = [&](int lo, int hi) {
    const auto t = triangle(lo);
    const CGAL::Orientation side_a = Ops::orient(t[0], t[1], t[2], a[0]);
    if (side_a == CGAL::COPLANAR) return false;
    for (const auto& p : a)
      if (Ops::orient(t[0], t[1], t[2], p) != side_a) return false;
    for (const auto& p : b)
      if (Ops::orient(t[0], t[1], t[2], p) != CGAL::opposite(side_a)) return false;
    for (const auto& p : a)
      for (const auto& q : b) {
        bool crossed = false;
        for (int i = lo; i < hi && !crossed; ++i) crossed = line_meets<Ops>(p, q, triangle(i));
        if (!crossed) return false;
      }
    return true;
  };
  if (patch_planar_[patch]) return begin < end && separates(begin, end);
  for (int i = begin; i < end; ++i)
    if (separates(i, i + 1)) return true;
  return false;
}

template <class Ops>
PairClass CgalVisibility::classify_points(std::span<const typename Ops::P> a, int patch_a,
                                          std::span<const typename Ops::P> b, int patch_b, const CGAL::Bbox_3& box,
                                          bool ends_on_patches, const std::vector<int>* candidates,
                                          std::vector<int>* occluders) const {
  if (occluders != nullptr) occluders->clear();
  using P = typename Ops::P;
  // Facing: some point of each must lie strictly in front of the other's plane.
  if (a.size() >= 3 && !any_strictly_in_front<Ops>(a, b)) return PairClass::kFacingAway;
  if (!any_strictly_in_front<Ops>(b, a)) return PairClass::kFacingAway;
  std::vector<P> pts(a.begin(), a.end());
  pts.insert(pts.end(), b.begin(), b.end());
  std::vector<Facet<Ops>> facets = detail::shaft_side_facets<Ops>(pts, a.size());
  if (facets.empty()) return PairClass::kFacingAway;  // coplanar: no segment leaves the plane
  // Only mutually facing pairs matter (estimate() counts no other), and they join A' to B' (see
  // the top of this file): the closed front half-spaces of both planes bound their shaft too.
  for (std::span<const P> poly : {a, b}) {
    if (poly.size() < 3) continue;
    const auto t = plane_triple<Ops>(poly);
    if (t[0] >= 0) facets.push_back({poly[t[0]], poly[t[1]], poly[t[2]]});
  }
  std::vector<std::pair<Point, Point>> probes;
  if constexpr (std::is_same_v<Ops, DoubleOps>) {
    // Probe segments strictly inside the shaft, near each vertex pair (see probe_segment_hits).
    // The explicit return type matters: deduced, it would be an Eigen expression referring to a
    // Vec3 temporary that dies with the call (AddressSanitizer: stack-use-after-scope).
    auto mean = [](std::span<const Point> p) -> Vec3 {
      double x = 0, y = 0, z = 0;
      for (const Point& q : p) x += q.x(), y += q.y(), z += q.z();
      return Vec3(x, y, z) / double(p.size());
    };
    const Vec3 centre = 0.5 * (mean(a) + mean(b));
    auto toward_centre = [&](const Point& p) { return to_point(0.9 * Vec3(p.x(), p.y(), p.z()) + 0.1 * centre); };
    auto strictly_inside = [&](const Point& p) {
      return std::all_of(facets.begin(), facets.end(),
                         [&](const Facet<Ops>& f) { return f.side(p) == CGAL::POSITIVE; });
    };
    for (const Point& p : a)
      for (const Point& q : b) {
        if (!options_.exact_shaft_contacts) break;
        const Point u = toward_centre(p), v = toward_centre(q);
        if (strictly_inside(u) && strictly_inside(v)) probes.emplace_back(u, v);
      }
  }
  std::vector<int> hits;
  const auto triangle_of = [this](std::size_t i) { return triangle_as<Ops>(i); };
  // The planes of the ends' patches, when the polygons lie in them exactly (classify() sends
  // elements on their patches' surfaces here; a non-planar patch has no one plane).
  const auto end_plane = [&](int patch, std::size_t count) {
    if (!ends_on_patches || patch < 0 || count < 3 || !patch_planar_[static_cast<std::size_t>(patch)]) return -2;
    const auto [begin, end] = patch_triangles_[static_cast<std::size_t>(patch)];
    return begin < end ? triangle_plane_[static_cast<std::size_t>(begin)] : -2;
  };
  const ShaftPlanes planes(std::span<const Facet<Ops>>(facets), magnitude_);
  ShaftTest<Ops, decltype(triangle_of)> test(triangles_, triangle_of, triangle_patch_, triangle_plane_,
                                             {end_plane(patch_a, a.size()), end_plane(patch_b, b.size())}, facets,
                                             planes, pts, probes, options_.exact_shaft_contacts, patch_a, patch_b,
                                             &hits);
  if (candidates == nullptr) {
    ShaftTraversal traversal(triangles_, triangle_boxes_, planes, test);
    if (!triangles_.empty()) tree_.traversal(box, traversal);
  } else {
    for (const int patch : *candidates) {
      if (patch == patch_a || patch == patch_b) continue;
      const auto [begin, end] = patch_triangles_[static_cast<std::size_t>(patch)];
      for (int i = begin; i < end; ++i) {
        const CGAL::Bbox_3& triangle_box = triangle_boxes_[static_cast<std::size_t>(i)];
        if (CGAL::do_overlap(box, triangle_box) && !planes.outside(triangle_box)) test(static_cast<std::size_t>(i));
      }
    }
  }
  if (hits.empty()) return PairClass::kFullyVisible;
  std::sort(hits.begin(), hits.end());
  hits.erase(std::unique(hits.begin(), hits.end()), hits.end());
  if (occluders != nullptr) *occluders = hits;
  for (int patch : hits)
    if (patch_hides<Ops>(patch, a, b)) return PairClass::kFullyHidden;
  return PairClass::kPartial;
}

PairClass CgalVisibility::classify_corners(std::span<const Point> a, int patch_a, std::span<const Point> b, int patch_b,
                                           bool ends_on_patches, const std::vector<int>* candidates,
                                           std::vector<int>* occluders) const {
  std::vector<Point> pts(a.begin(), a.end());
  pts.insert(pts.end(), b.begin(), b.end());
  return classify_points<DoubleOps>(a, patch_a, b, patch_b, bbox_of(pts), ends_on_patches, candidates, occluders);
}

PairClass CgalVisibility::classify_on_patches(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b,
                                              int patch_b, const std::vector<int>* candidates,
                                              std::vector<int>* occluders) const {
  // Each vertex stands for its projection onto its patch's surface (end_on()): the element the
  // solvers meant, whose vertices the doubles only approximate. Every predicate about those
  // points is exact (PatchOps).
  CGAL::Protect_FPU_rounding<true> upward;  // for PatchOps's intervals
  std::vector<PatchPoint> pa, pb;
  CGAL::Bbox_3 box;
  for (int side = 0; side < 2; ++side)
    for (const Vec3& v : side == 0 ? a : b) {
      const int patch = side == 0 ? patch_a : patch_b;
      const PatchEnd e = end_on(to_point(v), patch);
      PatchPoint q = patch_point(to_point(v), e.end.plane, e.end.axis);
      box += q.box.bbox();
      (side == 0 ? pa : pb).push_back(std::move(q));
    }
  pa = drop_collinear<PatchOps>(std::move(pa));
  pb = drop_collinear<PatchOps>(std::move(pb));
  return classify_points<PatchOps>(pa, patch_a, pb, patch_b, box, true, candidates, occluders);
}

// Sets `e` from a pair's class where the class settles it (hidden or facing away: 0, fully visible:
// 1, exactly); false for a partly visible pair, which is sampled.
bool settled(PairClass c, VisibilityEstimate* e) {
  e->pair_class = c;
  if (c == PairClass::kPartial) return false;
  e->fraction = c == PairClass::kFullyVisible ? 1.0 : 0.0;
  e->error = 0.0;
  return true;
}

VisibilityEstimate CgalVisibility::estimate(std::span<const Vec3> a, int patch_a, std::span<const Vec3> b, int patch_b,
                                            int samples, std::uint64_t seed) const {
  VisibilityEstimate e;
  if (settled(classify(a, patch_a, b, patch_b), &e)) return e;
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
  counters().segment_queries.add(static_cast<std::uint64_t>(facing));
  if (facing == 0) {  // the facing parts are too small for these samples to find
    e.fraction = 0.0;
    e.error = 0.5;
    return e;
  }
  e.fraction = double(visible) / facing;
  e.error = detail::fraction_error(visible, facing);
  return e;
}

VisibilityEstimate CgalVisibility::estimate_from_point(const Vec3& x, int patch_x, std::span<const Vec3> b, int patch_b,
                                                       int samples, std::uint64_t seed) const {
  counters().point_queries.add();
  VisibilityEstimate e;
  const Point px = to_point(x);
  if (settled(classify_corners(std::span<const Point>(&px, 1), patch_x, corners(b), patch_b), &e)) return e;
  detail::Rng rng(seed);
  std::vector<Vec2> ub;
  detail::stratified_unit_square(samples, rng, &ub);
  const detail::PolygonSampler sb(b);
  int visible = 0;
  for (const Vec2& s : ub) visible += blocked(px, patch_x, to_point(sb.point(s.x(), s.y())), patch_b) ? 0 : 1;
  counters().segment_queries.add(static_cast<std::uint64_t>(std::max(samples, 0)));
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
