// The number types behind the visibility oracle's exact answers about points that lie on patches
// (visibility.h, segment_blocked()): such a point is the projection of a double point onto its
// patch's plane along an axis, a rational point. Intervals (CGAL::Interval_nt, with the rounding
// mode set by the caller through CGAL::Protect_FPU_rounding) enclose it and decide almost every
// predicate; what they leave undecided is decided in exact integer arithmetic on homogeneous
// coordinates (Mpzf is exact for sums and products of doubles, and the projected point's
// homogeneous coordinates are polynomials in the input doubles: no division). Included only by
// the visibility sources.
#pragma once

#include <CGAL/Homogeneous.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Mpzf.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Uncertain.h>

#include <array>
#include <type_traits>

#include "hrad/core/types.h"

namespace hrad::detail {

using IntervalKernel = CGAL::Simple_cartesian<CGAL::Interval_nt_advanced>;
using HomogeneousKernel = CGAL::Homogeneous<CGAL::Mpzf>;

template <class K>
typename K::Point_3 kernel_point(double x, double y, double z) {
  if constexpr (std::is_same_v<K, HomogeneousKernel>)
    return typename K::Point_3(CGAL::Mpzf(x), CGAL::Mpzf(y), CGAL::Mpzf(z));
  else
    return typename K::Point_3(x, y, z);
}

template <class K>
typename K::Point_3 kernel_point(const Vec3& v) {
  return kernel_point<K>(v.x(), v.y(), v.z());
}

/// The point of the plane of triangle t (n . (p - t0) = 0, n = (t1 - t0) x (t2 - t0)) whose
/// coordinates on the axes other than `axis` are x's: p_k = t0_k - (n_i (x_i - t0_i) + n_j (x_j -
/// t0_j)) / n_k, as p = c / w in the number type R. n_k must not be 0.
template <class R>
void plane_point_coordinates(const std::array<Vec3, 3>& t, int axis, const Vec3& x, R (&c)[3], R& w) {
  R u[3], v[3], n[3];
  for (int k = 0; k < 3; ++k) u[k] = R(t[1][k]) - R(t[0][k]), v[k] = R(t[2][k]) - R(t[0][k]);
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  const int k = axis, i = (k + 1) % 3, j = (k + 2) % 3;
  w = n[k];
  c[i] = R(x[i]) * w;
  c[j] = R(x[j]) * w;
  c[k] = R(t[0][k]) * w - n[i] * (R(x[i]) - R(t[0][i])) - n[j] * (R(x[j]) - R(t[0][j]));
}

/// That point in kernel K (intervals: an enclosure; homogeneous: exact). With `plane` null, x.
template <class K>
typename K::Point_3 plane_point(const std::array<Vec3, 3>* plane, int axis, const Vec3& x) {
  if (plane == nullptr) return kernel_point<K>(x);
  using R = std::conditional_t<std::is_same_v<K, HomogeneousKernel>, CGAL::Mpzf, CGAL::Interval_nt_advanced>;
  R c[3], w;
  plane_point_coordinates(*plane, axis, x, c, w);
  if constexpr (std::is_same_v<K, HomogeneousKernel>) {
    if (CGAL::sign(w) == CGAL::NEGATIVE) return typename K::Point_3(-c[0], -c[1], -c[2], -w);
    return typename K::Point_3(c[0], c[1], c[2], w);
  } else {
    return typename K::Point_3(c[0] / w, c[1] / w, c[2] / w);
  }
}

template <class K>
typename K::Triangle_3 kernel_triangle(const std::array<Vec3, 3>& t) {
  return typename K::Triangle_3(kernel_point<K>(t[0]), kernel_point<K>(t[1]), kernel_point<K>(t[2]));
}

}  // namespace hrad::detail
