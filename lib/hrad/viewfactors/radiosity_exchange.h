// Radiant exchange solved by the radiosity solvers (full matrix, substructuring, hierarchical) on
// their own elements, through their one link operator and iteration loop (solve.h).
//
// The net radiation method (radiant_exchange.h) is a radiosity equation per element i,
// J_i = E_i + rho_i H_i with H_i the irradiance its links gather:
//   fixed temperature T:  E_i = eps sigma T^4,  rho_i = 1 - eps
//   fixed net flux q:     E_i = q,              rho_i = 1      (J_i = q + H_i)
// so each surface becomes one gray material and the solver's radiosity is J. The net flux an element
// sends is q_i = J_i - H_i with H_i the solver's own gathered irradiance (Solution::face_irradiance;
// not (J - E) / rho, which is 0 / 0 at eps = 1). Per surface: area-weighted means over its elements,
// q = mean J - mean H, and for fixed-flux surfaces the temperature of the mean emissive power,
// sigma T^4 = mean H + q / eps. Unlike the matrix method, the radiosity may vary over a surface.
// Gray: one band. The sky is at 0 K (an open model's remainder is lost, nothing comes back).
#pragma once

#include <vector>

#include "hrad/core/scene.h"
#include "hrad/solvers/solve.h"
#include "hrad/viewfactors/radiant_exchange.h"
#include "hrad/viewfactors/surface_units.h"

namespace hrad {

struct RadiosityExchange {
  RadiantExchange exchange;  ///< per unit; sky_heat = sum A_u q_u (0 in a closed model)
  SolveSummary summary;      ///< the solve's summary (method, elements, links, work, seconds)
  /// Largest |J - E - rho H| over the elements, relative to the largest |J|: how far the returned
  /// radiosity is from the equation it solves with the returned H (0 for a direct solve).
  double residual = 0.0;
};

/// Builds the exchange's scene (one gray material per unit, units.emissivity), solves it with
/// `options` (options.irradiance is set) and sums per unit. hrad::Error when sizes differ, an
/// emissivity is outside (0, 1], a temperature is negative, a face only obstructs (unit -1: it
/// has no condition), every surface has a fixed flux (no unique answer), or the solve fails.
RadiosityExchange solve_exchange_by_radiosity(const Scene& scene, const SurfaceUnits& units,
                                              const std::vector<SurfaceCondition>& conditions,
                                              const SolveOptions& options);

}  // namespace hrad
