// The touching rules of the visibility oracle (cgal_visibility.cpp) as predicates over any CGAL
// kernel: the double-coordinate kernel with exact predicates for points given as doubles, and
// interval and rational kernels for points that lie exactly on a patch (on_patch_segment.cpp).
// With an interval kernel an undecided comparison throws CGAL::Uncertain_conversion_exception,
// and the caller decides again in exact arithmetic. Included only by the visibility sources.
#pragma once

#include <CGAL/enum.h>
#include <CGAL/intersections.h>

namespace hrad::detail {

/// p lies in the closed triangle t; p is coplanar with t, t is not degenerate.
template <class K>
bool in_closed_coplanar_triangle(const typename K::Point_3& p, const typename K::Triangle_3& t) {
  for (int k = 0; k < 3; ++k)
    if (CGAL::Orientation(CGAL::coplanar_orientation(t[k], t[k + 1], t[k + 2], p)) == CGAL::NEGATIVE) return false;
  return true;
}

/// a lies in the closed triangle t and b != a is coplanar with it: does the segment leave a into
/// t? Yes iff b is on the inner side of (or on) every edge line through a (the tangent cone of t at a).
template <class K>
bool enters_triangle_from(const typename K::Point_3& a, const typename K::Point_3& b, const typename K::Triangle_3& t) {
  for (int k = 0; k < 3; ++k)
    if (CGAL::Orientation(CGAL::coplanar_orientation(t[k], t[k + 1], t[k + 2], a)) == CGAL::COLLINEAR &&
        CGAL::Orientation(CGAL::coplanar_orientation(t[k], t[k + 1], t[k + 2], b)) == CGAL::NEGATIVE)
      return false;
  return true;
}

/// The line through a and b, which lie strictly on opposite sides of t's plane, meets closed t:
/// its orientations against t's three edges are not of strictly opposite signs. `orient(p, q, r,
/// s)` is the orientation predicate of the points' kind.
template <class P, class T, class Orient>
bool line_meets_triangle(const P& a, const P& b, const T& t, Orient&& orient) {
  const CGAL::Orientation s0 = orient(a, b, t[0], t[1]);
  const CGAL::Orientation s1 = orient(a, b, t[1], t[2]);
  const CGAL::Orientation s2 = orient(a, b, t[2], t[0]);
  const bool pos = s0 == CGAL::POSITIVE || s1 == CGAL::POSITIVE || s2 == CGAL::POSITIVE;
  const bool neg = s0 == CGAL::NEGATIVE || s1 == CGAL::NEGATIVE || s2 == CGAL::NEGATIVE;
  return !(pos && neg);
}

template <class K>
bool crossing_inside(const typename K::Point_3& a, const typename K::Point_3& b, const typename K::Triangle_3& t) {
  return line_meets_triangle(a, b, t,
                             [](const auto& p, const auto& q, const auto& r, const auto& s) -> CGAL::Orientation {
                               return CGAL::orientation(p, q, r, s);
                             });
}

/// The open segment (a, b), a != b, meets the closed non-degenerate triangle t.
template <class K>
bool open_segment_meets_triangle(const typename K::Point_3& a, const typename K::Point_3& b,
                                 const typename K::Triangle_3& t) {
  const CGAL::Orientation oa = CGAL::orientation(t[0], t[1], t[2], a);
  const CGAL::Orientation ob = CGAL::orientation(t[0], t[1], t[2], b);
  if (oa == ob && oa != CGAL::COPLANAR) return false;  // same open side
  if (oa != CGAL::COPLANAR && ob != CGAL::COPLANAR) return crossing_inside<K>(a, b, t);
  if (oa != CGAL::COPLANAR || ob != CGAL::COPLANAR) return false;  // meets the plane at an endpoint only
  // The segment lies in t's plane.
  const bool a_in = in_closed_coplanar_triangle<K>(a, t);
  const bool b_in = in_closed_coplanar_triangle<K>(b, t);
  if (a_in && b_in) return true;
  if (a_in) return enters_triangle_from<K>(a, b, t);
  if (b_in) return enters_triangle_from<K>(b, a, t);
  return bool(CGAL::do_intersect(typename K::Segment_3(a, b), t));  // neither endpoint inside: any contact is interior
}

}  // namespace hrad::detail
