#include "hrad/visibility/on_patch_segment.h"

#include <algorithm>
#include <cmath>

#include "hrad/visibility/exact_kernels.h"
#include "hrad/visibility/segment_triangle.h"

namespace hrad::detail {
namespace {

using IK = IntervalKernel;
using HK = HomogeneousKernel;
using I = CGAL::Interval_nt_advanced;

IK::Point_3 from_bounds(const std::array<double, 6>& b) {
  return IK::Point_3(I(b[0], b[1]), I(b[2], b[3]), I(b[4], b[5]));
}

// The sign of orient3d(p, q, r, s) = ((q - p) x (r - p)) . (s - p) in doubles when it is certain
// for every placement of two of the points within `w` of the given ones (the other two exact),
// else 0. A semi-static filter (Shewchuk 1997; Meyer & Pion 2008): with L at least the largest
// coordinate difference among the points (`spread`, e.g. the extent of a box holding them) plus 2w,
// the rounding error is below 2^-40 L^3 (about 2^-50 times a few terms in fact), and moving two
// points by w changes the determinant by less than 12 L^2 w per point.
int certain_orientation(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, double spread, double w) {
  const Vec3 u = q - p, v = r - p, x = s - p;
  const double l = spread + 2.0 * w;
  const double det = u.cross(v).dot(x);
  const double bound = 0x1p-40 * l * l * l + 24.0 * l * l * w;
  if (!std::isfinite(det) || !std::isfinite(bound)) return 0;
  return det > bound ? 1 : det < -bound ? -1 : 0;
}

Vec3 middle(const std::array<double, 6>& b) {
  return Vec3(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
}

double width(const std::array<double, 6>& b) { return std::max({b[1] - b[0], b[3] - b[2], b[5] - b[4]}); }

}  // namespace

OnPatchSegment::OnPatchSegment(const SegmentEnd& a, const SegmentEnd& b) : a_(a), b_(b) {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    const IK::Point_3 pa = plane_point<IK>(a.plane, a.axis, a.x), pb = plane_point<IK>(b.plane, b.axis, b.x);
    for (int k = 0; k < 3; ++k) {
      a_bounds_[2 * k] = pa[k].inf(), a_bounds_[2 * k + 1] = pa[k].sup();
      b_bounds_[2 * k] = pb[k].inf(), b_bounds_[2 * k + 1] = pb[k].sup();
    }
  }
  // The filter's points and their reach (misses()), once per segment rather than per triangle.
  a_mid_ = middle(a_bounds_);
  b_mid_ = middle(b_bounds_);
  reach_ = std::max(width(a_bounds_), width(b_bounds_));
}

template <class Decide>
bool OnPatchSegment::decide(Decide&& decide) const {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    try {
      return decide(IK(), from_bounds(a_bounds_), from_bounds(b_bounds_));
    } catch (const CGAL::Uncertain_conversion_exception&) {
    }
  }
  return decide(HK(), plane_point<HK>(a_.plane, a_.axis, a_.x), plane_point<HK>(b_.plane, b_.axis, b_.x));
}

bool OnPatchSegment::degenerate() const {
  for (int k = 0; k < 3; ++k)  // disjoint enclosures: distinct points (plain comparisons, exact)
    if (a_bounds_[2 * k + 1] < b_bounds_[2 * k] || b_bounds_[2 * k + 1] < a_bounds_[2 * k]) return false;
  return decide([](auto, const auto& p, const auto& q) { return bool(p == q); });
}

int OnPatchSegment::settled(const Triangle3& t, bool a_in_plane, bool b_in_plane) const {
  // The cheap answers of meets() in doubles, taken only where the filter makes them certain for
  // the exact points: both ends strictly on one side of t's plane, or the segment's line passing
  // beside t, miss; both ends strictly on opposite sides and the line strictly inside t's three
  // edges meets (a blocked ray, which otherwise costs an interval evaluation to confirm). Most
  // candidate triangles of a ray are settled here, without a rounding-mode switch.
  const Vec3& pa = a_mid_;
  const Vec3& pb = b_mid_;
  const double w = reach_;
  // One spread for the five tests: the extent of the box around the segment and the triangle.
  const Vec3 lo = pa.cwiseMin(pb).cwiseMin(t[0]).cwiseMin(t[1]).cwiseMin(t[2]);
  const Vec3 hi = pa.cwiseMax(pb).cwiseMax(t[0]).cwiseMax(t[1]).cwiseMax(t[2]);
  const double spread = (hi - lo).maxCoeff();
  int oa = 0, ob = 0;
  if (!a_in_plane && !b_in_plane) {
    oa = certain_orientation(t[0], t[1], t[2], pa, spread, w);
    ob = certain_orientation(t[0], t[1], t[2], pb, spread, w);
    if (oa != 0 && oa == ob) return -1;
  }
  bool pos = false, neg = false, certain = true;
  for (int m = 0; m < 3; ++m) {
    const int o = certain_orientation(pa, pb, t[m], t[(m + 1) % 3], spread, w);
    pos |= o > 0;
    neg |= o < 0;
    certain = certain && o != 0;
  }
  if (pos && neg) return -1;
  // open_segment_meets_triangle(): ends strictly on opposite sides, the line inside every edge.
  if (oa != 0 && ob == -oa && certain) return 1;
  return 0;
}

bool OnPatchSegment::meets(const Triangle3& t, bool a_in_plane, bool b_in_plane) const {
  if (const int known = settled(t, a_in_plane, b_in_plane); known != 0) return known > 0;
  return decide([&](auto kernel, const auto& p, const auto& q) {
    using K = decltype(kernel);
    const typename K::Triangle_3 tri = kernel_triangle<K>(t);
    // Cheap answers first, each exact where it is certain: an end known to lie in t's plane
    // (a twin of its patch) needs no arithmetic; a segment whose line passes beside t (its
    // orientations against t's edges have strict opposite signs) misses it, whatever side
    // of t's plane an end near it lies on.
    const auto side = [&](bool in_plane, const auto& x) {
      return in_plane ? CGAL::make_uncertain(CGAL::COPLANAR)
                      : CGAL::make_uncertain(CGAL::orientation(tri[0], tri[1], tri[2], x));
    };
    const auto oa = side(a_in_plane, p), ob = side(b_in_plane, q);
    if (CGAL::certainly(oa == ob) && CGAL::certainly(oa != CGAL::COPLANAR)) return false;
    if (CGAL::certainly(oa == CGAL::COPLANAR) && CGAL::certainly(ob != CGAL::COPLANAR)) return false;
    if (CGAL::certainly(ob == CGAL::COPLANAR) && CGAL::certainly(oa != CGAL::COPLANAR)) return false;
    bool pos = false, neg = false;
    for (int m = 0; m < 3; ++m) {
      const auto o = CGAL::make_uncertain(CGAL::orientation(p, q, tri[m], tri[(m + 1) % 3]));
      pos |= CGAL::certainly(o == CGAL::POSITIVE);
      neg |= CGAL::certainly(o == CGAL::NEGATIVE);
    }
    if (pos && neg) return false;
    return open_segment_meets_triangle<K>(p, q, tri);
  });
}

bool OnPatchSegment::facing(const Triangle3& ta, const Triangle3& tb) const {
  {
    // In doubles where the filter makes both signs certain for the exact points.
    Vec3 lo = a_mid_.cwiseMin(b_mid_), hi = a_mid_.cwiseMax(b_mid_);
    for (const Triangle3* t : {&ta, &tb})
      for (const Vec3& v : *t) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const double spread = (hi - lo).maxCoeff();
    const int ob = certain_orientation(ta[0], ta[1], ta[2], b_mid_, spread, reach_);
    const int oa = certain_orientation(tb[0], tb[1], tb[2], a_mid_, spread, reach_);
    if (ob < 0 || oa < 0) return false;
    if (ob > 0 && oa > 0) return true;
  }
  return decide([&](auto kernel, const auto& p, const auto& q) {
    using K = decltype(kernel);
    const auto u = kernel_triangle<K>(ta), v = kernel_triangle<K>(tb);
    return CGAL::Orientation(CGAL::orientation(u[0], u[1], u[2], q)) == CGAL::POSITIVE &&
           CGAL::Orientation(CGAL::orientation(v[0], v[1], v[2], p)) == CGAL::POSITIVE;
  });
}

}  // namespace hrad::detail
