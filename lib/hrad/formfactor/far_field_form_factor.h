// A_from * F_from_to by product Gauss quadrature of the area-area kernel, for pieces far apart
// relative to their size, where the contour sum would cancel.
#pragma once

#include <span>

#include "hrad/core/types.h"

namespace hrad::detail {

/// e^-37, the tolerance of m = 18.5 / ln rho points: below double rounding for the kernel's sums.
inline constexpr double kFarFieldFullPrecision = 8.533047625744066e-17;

/// The number of Gauss points per direction that integrates the kernel over two pieces of radius
/// <= `radius` with centres `distance` apart to ~`rel_tol` (default: full double precision), or 0
/// when they are too close for kMaxFarOrder points. The kernel is analytic in each piece except
/// where r = 0 (complex continuation), at least distance - 2 radius away; a Gauss rule on a panel of
/// half-width R with the nearest singularity at d from its centre converges like rho^(-2m),
/// rho = d/R + sqrt((d/R)^2 + 1) (Trefethen 2008, Thm 4.5), so m = ln(1/rel_tol) / (2 ln rho).
/// A looser tolerance gives a lower order and admits closer pairs.
int far_field_order(double distance, double radius_from, double radius_to, double rel_tol = kFarFieldFullPrecision);

inline constexpr int kMaxFarOrder = 8;

/// sum_x sum_y w_x w_y cos(theta_x) cos(theta_y) / (pi r^2) over the triangles (a0 a1 a2) and
/// (b0 b1 b2) with `order` points per direction (collapsed Gauss rule on each triangle).
double far_field_area_factor(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& na, const Vec3& b0,
                             const Vec3& b1, const Vec3& b2, const Vec3& nb, int order);

}  // namespace hrad::detail
