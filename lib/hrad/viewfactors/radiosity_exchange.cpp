#include "hrad/viewfactors/radiosity_exchange.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/core/solution.h"
#include "hrad/geometry/polygon.h"

namespace hrad {

RadiosityExchange solve_exchange_by_radiosity(const Scene& scene, const SurfaceUnits& units,
                                              const std::vector<SurfaceCondition>& conditions,
                                              const SolveOptions& options) {
  const std::size_t n = static_cast<std::size_t>(units.size());
  if (conditions.size() != n) throw Error(fmt::format("{} boundary conditions for {} surfaces", conditions.size(), n));
  if (units.emissivity.size() != n) throw Error(fmt::format("{} emissivities for {} surfaces", units.emissivity.size(), n));
  bool any_temperature = false;
  Scene s = scene;
  s.materials.assign(n, Material{});
  for (std::size_t u = 0; u < n; ++u) {
    const double eps = units.emissivity[u];
    const SurfaceCondition& c = conditions[u];
    if (!(eps > 0.0 && eps <= 1.0)) throw Error(fmt::format("surface {}: emissivity {} is not in (0, 1]", u, eps));
    if (!std::isfinite(c.value)) throw Error(fmt::format("surface {}: condition {} is not finite", u, c.value));
    Material& m = s.materials[u];
    m.name = units.names[u];
    if (c.kind == SurfaceCondition::Kind::kTemperature) {
      if (!(c.value >= 0.0)) throw Error(fmt::format("surface {}: temperature {} K is negative", u, c.value));
      any_temperature = true;
      m.emission = Rgb::Constant(eps * kStefanBoltzmann * std::pow(c.value, 4));
      m.reflectance = Rgb::Constant(1.0 - eps);
    } else {
      m.emission = Rgb::Constant(c.value);
      m.reflectance = Rgb::Constant(1.0);
    }
  }
  if (!any_temperature)
    throw Error("radiant exchange: every surface has a fixed flux; give at least one a temperature");
  for (Patch& p : s.patches) {
    const int u = units.of_face[static_cast<std::size_t>(p.face)];
    if (u < 0)
      throw Error(fmt::format("radiant exchange: face {} only obstructs; the radiosity solvers need a condition on "
                              "every surface (use the matrix method)",
                              p.face));
    p.material = u;
  }
  for (std::size_t f = 0; f < s.faces.size(); ++f) s.faces[f].material = units.of_face[f];

  SolveOptions o = options;
  o.irradiance = true;
  Solution sol;
  RadiosityExchange r;
  r.summary = solve(s, o, &sol);
  if (r.summary.termination == Termination::kFailed)
    throw Error(fmt::format("radiant exchange: {} failed: {}", to_string(o.method), r.summary.message));

  std::vector<double> area(n, 0.0), j(n, 0.0), h(n, 0.0);
  double largest = 0.0, residual = 0.0;
  std::vector<Vec3> polygon;
  for (std::size_t f = 0; f < sol.faces.size(); ++f) {
    polygon.clear();
    for (int v : sol.faces[f]) polygon.push_back(sol.vertices[static_cast<std::size_t>(v)]);
    const double a = polygon_area(polygon);
    const int patch = sol.face_patch[f];
    const auto u = static_cast<std::size_t>(s.patches[static_cast<std::size_t>(patch)].material);
    const double jf = sol.face_radiosity[f][0], hf = sol.face_irradiance[f][0];
    area[u] += a;
    j[u] += a * jf;
    h[u] += a * hf;
    const Material& m = s.materials[u];
    largest = std::max(largest, std::abs(jf));
    residual = std::max(residual, std::abs(jf - m.emission[0] - m.reflectance[0] * hf));
  }
  r.residual = largest > 0.0 ? residual / largest : residual;
  RadiantExchange& x = r.exchange;
  x.temperature.resize(n);
  x.heat_flux.resize(n);
  x.radiosity.resize(n);
  x.irradiation.resize(n);
  for (std::size_t u = 0; u < n; ++u) {
    const double jm = j[u] / area[u], hm = h[u] / area[u];
    x.radiosity[u] = jm;
    x.irradiation[u] = hm;
    x.heat_flux[u] = jm - hm;
    if (conditions[u].kind == SurfaceCondition::Kind::kTemperature) {
      x.temperature[u] = conditions[u].value;
    } else {
      const double e4 = hm + conditions[u].value / units.emissivity[u];
      if (e4 < 0.0)
        throw Error(fmt::format("surface {}: no temperature gives net flux {} W/m^2", u, conditions[u].value));
      x.temperature[u] = std::pow(e4 / kStefanBoltzmann, 0.25);
    }
    x.sky_heat += area[u] * x.heat_flux[u];
  }
  return r;
}

}  // namespace hrad
