// Radiant exchange in a gray, diffuse enclosure described by its view-factor matrix: each surface
// has an emissivity eps (reflectivity 1 - eps) and either a fixed temperature or a fixed net heat
// flux; the sky (1 - row sum, for open models) is black at a given temperature.
//
// Net radiation method (Hottel & Sarofim 1967, "Radiative Transfer", ch. 3; Siegel & Howell,
// "Thermal Radiation Heat Transfer", ch. 6): with radiosity J_i and irradiation
// H_i = sum_j F_ij J_j + F_i,sky sigma T_sky^4, each surface has J_i = eps_i sigma T_i^4 + (1 - eps_i) H_i,
// and its net outgoing flux is q_i = J_i - H_i, so
//   fixed temperature:  J_i - (1 - eps_i) sum_j F_ij J_j = eps_i sigma T_i^4 + (1 - eps_i) F_i,sky sigma T_sky^4
//   fixed net flux:     J_i - sum_j F_ij J_j             = q_i + F_i,sky sigma T_sky^4
// one sparse linear system (Eigen's SparseLU) in J; then q_i = eps_i (sigma T_i^4 - H_i) or
// sigma T_i^4 = H_i + q_i / eps_i.
//
// Gebhart's absorption factors (Gebhart 1961, "Surface radiation", and "Heat Transfer" ch. 5),
// for all temperatures fixed: B_ij, the share of what i emits that j absorbs, solves
// (I - F diag(rho)) B = F diag(eps) (the sky a black absorber, B_i,sky = F_i,sky + sum_k F_ik rho_k B_k,sky);
// Hottel's total exchange areas are S_iS_j = A_i eps_i B_ij, and Q_i = sum_j S_iS_j sigma (T_i^4 - T_j^4)
// with the sky among the j. Dense: for checking and small models.
#pragma once

#include <vector>

#include "hrad/viewfactors/view_factor_matrix.h"

namespace hrad {

/// Stefan-Boltzmann constant, W m^-2 K^-4 (CODATA 2018, exact in the SI since 2019).
inline constexpr double kStefanBoltzmann = 5.670374419e-8;

struct SurfaceCondition {
  enum class Kind { kTemperature, kHeatFlux } kind = Kind::kTemperature;
  double value = 0.0;  ///< K, or W/m^2 leaving the surface (net)
};

struct RadiantExchange {
  std::vector<double> temperature;  ///< K (given or solved)
  std::vector<double> heat_flux;    ///< net W/m^2 leaving each surface (given or solved)
  std::vector<double> radiosity;    ///< J, W/m^2
  std::vector<double> irradiation;  ///< H, W/m^2
  double sky_heat = 0.0;            ///< W the sky absorbs net (sum of A_i q_i)
};

/// hrad::Error when sizes differ, an emissivity is outside (0, 1], a temperature is negative, or
/// the system is singular (e.g. every surface has a fixed flux in a closed enclosure).
RadiantExchange solve_radiant_exchange(const ViewFactorMatrix& f, const std::vector<double>& emissivity,
                                       const std::vector<SurfaceCondition>& conditions, double sky_temperature = 0.0);

/// Gebhart's factors B (n x (n + 1), the last column the sky), row-major.
std::vector<double> gebhart_factors(const ViewFactorMatrix& f, const std::vector<double>& emissivity);

/// Net heat leaving each surface (W) at fixed temperatures, from Hottel's total exchange areas.
std::vector<double> net_heat_by_exchange_areas(const ViewFactorMatrix& f, const std::vector<double>& emissivity,
                                               const std::vector<double>& temperature, double sky_temperature = 0.0);

}  // namespace hrad
