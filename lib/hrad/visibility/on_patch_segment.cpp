#include "hrad/visibility/on_patch_segment.h"

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

}  // namespace

OnPatchSegment::OnPatchSegment(const SegmentEnd& a, const SegmentEnd& b) : a_(a), b_(b) {
  CGAL::Protect_FPU_rounding<true> upward;
  const IK::Point_3 pa = plane_point<IK>(a.plane, a.axis, a.x), pb = plane_point<IK>(b.plane, b.axis, b.x);
  for (int k = 0; k < 3; ++k) {
    a_bounds_[2 * k] = pa[k].inf(), a_bounds_[2 * k + 1] = pa[k].sup();
    b_bounds_[2 * k] = pb[k].inf(), b_bounds_[2 * k + 1] = pb[k].sup();
  }
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

bool OnPatchSegment::meets(const Triangle3& t, bool a_in_plane, bool b_in_plane) const {
  return decide([&](auto kernel, const auto& p, const auto& q) {
    using K = decltype(kernel);
    const typename K::Triangle_3 tri = kernel_triangle<K>(t);
    // Cheap answers first, each exact where it is certain: an end known to lie in t's plane
    // (a twin of its patch) needs no arithmetic; a segment whose line passes beside t (its
    // orientations against t's edges have strict opposite signs) misses it, whatever side
    // of t's plane an end near it lies on.
    const auto side = [&](bool in_plane, const auto& x) {
      return in_plane ? CGAL::make_uncertain(CGAL::COPLANAR) : CGAL::make_uncertain(CGAL::orientation(tri[0], tri[1], tri[2], x));
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
  return decide([&](auto kernel, const auto& p, const auto& q) {
    using K = decltype(kernel);
    const auto u = kernel_triangle<K>(ta), v = kernel_triangle<K>(tb);
    return CGAL::Orientation(CGAL::orientation(u[0], u[1], u[2], q)) == CGAL::POSITIVE &&
           CGAL::Orientation(CGAL::orientation(v[0], v[1], v[2], p)) == CGAL::POSITIVE;
  });
}

}  // namespace hrad::detail
