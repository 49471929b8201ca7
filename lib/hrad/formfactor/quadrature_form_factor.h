// Reference: adaptive quadrature of the area-area form factor integral.
#pragma once

#include <cstddef>
#include <span>

#include "hrad/core/types.h"

namespace hrad {

struct QuadratureFormFactor {
  double value = 0.0;           // F_from_to
  double error_estimate = 0.0;  // estimated absolute error of value
  std::size_t evaluations = 0;  // point-to-polygon evaluations
  bool converged = false;       // error_estimate <= rel_tol * value (or the factor is 0)
};

/// F_from_to = 1/A_from int_from F_{dA->to}(x) dA(x): the inner area integral done exactly by
/// Lambert's contour formula (point_to_polygon), the outer by globally adaptive quadrature on
/// triangles (collapsed Gauss rule of order 5, each triangle split 1-to-4, the error of a triangle
/// estimated as |parent - sum of children|; Berntsen & Espelid 1992 style global subdivision).
/// It shares no code with polygon_to_polygon beyond point_to_polygon, which is itself checked
/// against Howell's B-3 and its perpendicular counterpart. Stops at `rel_tol` or after
/// `max_evaluations` (converged = false). Usage:
///   QuadratureFormFactor q = quadrature_form_factor(from, to, 1e-10);
QuadratureFormFactor quadrature_form_factor(std::span<const Vec3> from, std::span<const Vec3> to, double rel_tol,
                                            std::size_t max_evaluations = 50'000'000);

}  // namespace hrad
