// Exact decisions about a segment whose ends lie on patches. A sample point of a patch, computed in
// doubles, is off the patch's plane by its rounding (unless the plane is axis-aligned or the point
// happens to be exact); a back-to-back twin of the patch, or the rest of a closed surface around
// it, then decides the segment by which side of the plane the rounding fell on. Here each end
// stands for a point exactly on its patch, and every predicate about it is decided exactly.
// CGAL stays in on_patch_segment.cpp.
#pragma once

#include <array>

#include "hrad/core/types.h"

namespace hrad::detail {

using Triangle3 = std::array<Vec3, 3>;

/// An end of a segment: with `plane` null the point `x` itself; otherwise the point of the plane of
/// the non-degenerate triangle `*plane` whose coordinates on the two axes other than `axis` are
/// those of x (its projection along `axis`, a rational point). `axis` must be one along which the
/// triangle's normal has a non-zero component (its largest one, for conditioning).
struct SegmentEnd {
  Vec3 x = Vec3::Zero();
  const Triangle3* plane = nullptr;
  int axis = 0;
};

/// The segment between the rational points that two ends stand for. Every answer is exact:
/// interval arithmetic first, rationals when an interval comparison is undecided. The triangles
/// must outlive the object.
class OnPatchSegment {
 public:
  OnPatchSegment(const SegmentEnd& a, const SegmentEnd& b);
  /// The two points coincide (the open segment is empty).
  bool degenerate() const;
  /// The open segment meets the closed non-degenerate triangle t (the touching rules of
  /// segment_triangle.h). `a_in_plane` / `b_in_plane`: the caller knows that the end lies in t's
  /// plane (t is coplanar with the end's triangle), which spares an exact zero test.
  bool meets(const Triangle3& t, bool a_in_plane = false, bool b_in_plane = false) const;
  /// b's point lies strictly on the positive side of the oriented plane of `ta` (counter-clockwise
  /// seen from the positive side) and a's point strictly on the positive side of `tb`'s.
  bool facing(const Triangle3& ta, const Triangle3& tb) const;

 private:
  /// meets() where doubles prove it (a filter in front of the exact test): -1 misses, 1 meets, 0
  /// not settled.
  int settled(const Triangle3& t, bool a_in_plane, bool b_in_plane) const;
  template <class Decide>
  bool decide(Decide&& decide) const;

  SegmentEnd a_, b_;
  std::array<double, 6> a_bounds_{}, b_bounds_{};     ///< interval enclosures: lo x, hi x, lo y, ...
  Vec3 a_mid_ = Vec3::Zero(), b_mid_ = Vec3::Zero();  ///< the enclosures' middles
  double reach_ = 0.0;                                ///< the wider enclosure's width
};

}  // namespace hrad::detail
