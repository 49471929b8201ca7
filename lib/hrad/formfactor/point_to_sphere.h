// The form factor from a differential planar element to a sphere, the sphere partly or wholly
// above the element's horizon (Howell, "A Catalog of Radiation Heat Transfer Configuration
// Factors": differential planar element to a sphere whose centre lies at angle phi from the
// element's normal). With H = D / R (D the distance to the centre, R the radius):
//   phi <= acos(1 / H):           F = cos(phi) / H^2
//   phi >= pi - acos(1 / H):      F = 0
//   otherwise:                    F = 1/2 - asin(sqrt(H^2 - 1) / (H sin phi)) / pi
//                                     + cos(phi) acos(-sqrt(H^2 - 1) cot phi) / (pi H^2)
//                                     - sqrt(H^2 - 1) sqrt(1 - H^2 cos^2 phi) / (pi H^2).
// A point inside the sphere sees it with its whole hemisphere: F = 1.
#pragma once

#include "hrad/core/types.h"

namespace hrad {

/// F(dA_x -> sphere): the element at x with unit normal n, the sphere of `radius` about `centre`.
double point_to_sphere(const Vec3& x, const Vec3& n, const Vec3& centre, double radius);

}  // namespace hrad
