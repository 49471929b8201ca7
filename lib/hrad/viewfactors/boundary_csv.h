// Boundary conditions for radiant exchange from CSV: the header surface,temperature,heat_flux and
// one row per surface (its 0-based row in the matrix), exactly one of temperature (K) and
// heat_flux (net W/m^2 leaving the surface) filled. Every surface must appear once. Defects are
// one-line hrad::Errors naming file:line.
//
//   surface,temperature,heat_flux
//   0,600,
//   1,,0
#pragma once

#include <string>
#include <vector>

#include "hrad/viewfactors/radiant_exchange.h"

namespace hrad {

std::vector<SurfaceCondition> read_boundary_csv(const std::string& path, int surfaces);

}  // namespace hrad
