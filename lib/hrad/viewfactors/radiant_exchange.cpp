#include "hrad/viewfactors/radiant_exchange.h"

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <cmath>

#include <fmt/format.h>

#include "hrad/core/error.h"

namespace hrad {
namespace {

double black(double t) { return kStefanBoltzmann * t * t * t * t; }

void check(const ViewFactorMatrix& f, const std::vector<double>& emissivity) {
  if (emissivity.size() != static_cast<std::size_t>(f.n))
    throw Error(fmt::format("{} emissivities for {} surfaces", emissivity.size(), f.n));
  for (std::size_t i = 0; i < emissivity.size(); ++i)
    if (!(emissivity[i] > 0.0 && emissivity[i] <= 1.0))
      throw Error(fmt::format("surface {}: emissivity {} is not in (0, 1]", i, emissivity[i]));
}

}  // namespace

RadiantExchange solve_radiant_exchange(const ViewFactorMatrix& f, const std::vector<double>& emissivity,
                                       const std::vector<SurfaceCondition>& conditions, double sky_temperature) {
  check(f, emissivity);
  if (conditions.size() != static_cast<std::size_t>(f.n))
    throw Error(fmt::format("{} boundary conditions for {} surfaces", conditions.size(), f.n));
  if (!(sky_temperature >= 0.0)) throw Error(fmt::format("sky temperature {} K is negative", sky_temperature));
  const int n = f.n;
  const double sky = black(sky_temperature);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(f.nonzeros() + static_cast<std::size_t>(n));
  Eigen::VectorXd rhs(n);
  for (int i = 0; i < n; ++i) {
    const auto& c = conditions[static_cast<std::size_t>(i)];
    const double eps = emissivity[static_cast<std::size_t>(i)];
    const double to_sky = std::max(0.0, 1.0 - f.row_sum(i));
    const bool fixed_t = c.kind == SurfaceCondition::Kind::kTemperature;
    if (fixed_t && !(c.value >= 0.0)) throw Error(fmt::format("surface {}: temperature {} K is negative", i, c.value));
    const double keep = fixed_t ? 1.0 - eps : 1.0;  // the share of H that J carries on
    t.emplace_back(i, i, 1.0);
    for (std::int64_t k = f.row_begin[static_cast<std::size_t>(i)]; k < f.row_begin[static_cast<std::size_t>(i) + 1];
         ++k)
      t.emplace_back(i, f.column[static_cast<std::size_t>(k)], -keep * f.factor(i, k));
    rhs[i] = fixed_t ? eps * black(c.value) + keep * to_sky * sky : c.value + to_sky * sky;
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(a);
  if (lu.info() != Eigen::Success)
    throw Error("radiant exchange: the system is singular (is every surface at a fixed flux?)");
  const Eigen::VectorXd j = lu.solve(rhs);
  RadiantExchange r;
  r.radiosity.assign(j.data(), j.data() + n);
  r.irradiation.resize(static_cast<std::size_t>(n));
  r.temperature.resize(static_cast<std::size_t>(n));
  r.heat_flux.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    double h = std::max(0.0, 1.0 - f.row_sum(i)) * sky;
    for (std::int64_t k = f.row_begin[ui]; k < f.row_begin[ui + 1]; ++k)
      h += f.factor(i, k) * j[f.column[static_cast<std::size_t>(k)]];
    r.irradiation[ui] = h;
    if (conditions[ui].kind == SurfaceCondition::Kind::kTemperature) {
      r.temperature[ui] = conditions[ui].value;
      r.heat_flux[ui] = emissivity[ui] * (black(conditions[ui].value) - h);
    } else {
      r.heat_flux[ui] = conditions[ui].value;
      const double e4 = h + conditions[ui].value / emissivity[ui];
      if (e4 < 0.0)
        throw Error(fmt::format("surface {}: no temperature gives net flux {} W/m^2", i, conditions[ui].value));
      r.temperature[ui] = std::pow(e4 / kStefanBoltzmann, 0.25);
    }
    r.sky_heat += f.area[ui] * r.heat_flux[ui];
  }
  return r;
}

std::vector<double> gebhart_factors(const ViewFactorMatrix& f, const std::vector<double>& emissivity) {
  check(f, emissivity);
  const int n = f.n;
  Eigen::MatrixXd fm = Eigen::MatrixXd::Zero(n, n + 1);
  for (int i = 0; i < n; ++i) {
    for (std::int64_t k = f.row_begin[static_cast<std::size_t>(i)]; k < f.row_begin[static_cast<std::size_t>(i) + 1];
         ++k)
      fm(i, f.column[static_cast<std::size_t>(k)]) = f.factor(i, k);
    fm(i, n) = std::max(0.0, 1.0 - f.row_sum(i));
  }
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd rhs(n, n + 1);
  for (int j = 0; j < n; ++j) a.col(j) -= fm.col(j) * (1.0 - emissivity[static_cast<std::size_t>(j)]);
  for (int j = 0; j <= n; ++j) rhs.col(j) = fm.col(j) * (j < n ? emissivity[static_cast<std::size_t>(j)] : 1.0);
  const Eigen::MatrixXd b = a.partialPivLu().solve(rhs);
  std::vector<double> out(static_cast<std::size_t>(n) * static_cast<std::size_t>(n + 1));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= n; ++j)
      out[static_cast<std::size_t>(i) * static_cast<std::size_t>(n + 1) + static_cast<std::size_t>(j)] = b(i, j);
  return out;
}

std::vector<double> net_heat_by_exchange_areas(const ViewFactorMatrix& f, const std::vector<double>& emissivity,
                                               const std::vector<double>& temperature, double sky_temperature) {
  const std::vector<double> b = gebhart_factors(f, emissivity);
  const int n = f.n;
  std::vector<double> q(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const double s = f.area[ui] * emissivity[ui];  // S_iS_j = A_i eps_i B_ij
    for (int j = 0; j <= n; ++j) {
      const double tj = j < n ? temperature[static_cast<std::size_t>(j)] : sky_temperature;
      q[ui] += s * b[ui * static_cast<std::size_t>(n + 1) + static_cast<std::size_t>(j)] *
               (black(temperature[ui]) - black(tj));
    }
  }
  return q;
}

}  // namespace hrad
