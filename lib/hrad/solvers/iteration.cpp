#include "hrad/solvers/iteration.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace hrad {

bool iterate(SolverContext& ctx, const PushPull& push_pull, std::span<const LinkOperator* const> operators,
             NodeField& field, double bound) {
  while (true) {
    field.clear_gathered();
    for (const LinkOperator* op : operators) op->gather(field);
    const LeafChange c = push_pull.push_pull(field);
    if (ctx.record_iteration(stopping_change(c))) break;
    double largest = 0.0;
    for (std::size_t p = 0; p < ctx.scene().patches.size(); ++p)
      largest = std::max(largest, field.radiosity[p].maxCoeff());
    if (largest > 2.0 * bound) {
      ctx.set_failed(
          fmt::format("diverging: the mean radiosity of a patch ({}) passed twice the bound E_max / "
                      "(1 - rho_max) = {} after {} iterations: the factors sum above 1 on some elements "
                      "(try a smaller --feps or more --visibility-samples)",
                      largest, bound, ctx.summary().iterations));
      break;
    }
  }
  return ctx.summary().termination == Termination::kConverged;
}

double stopping_change(const LeafChange& c) {
  if (!std::isfinite(c.change) || !std::isfinite(c.reflected) || !std::isfinite(c.power_change) ||
      !std::isfinite(c.reflected_power))
    return NAN;
  const double largest = c.reflected > 0.0 ? c.change / c.reflected : c.change;
  const double power = c.reflected_power > 0.0 ? c.power_change / c.reflected_power : c.power_change;
  return std::max(largest, power);
}

double radiosity_bound(const Scene& scene) {
  double e = 0.0, rho = 0.0;
  for (const Material& m : scene.materials) {
    e = std::max(e, m.emission.maxCoeff());
    rho = std::max(rho, m.reflectance.maxCoeff());
  }
  return rho < 1.0 ? e / (1.0 - rho) : INFINITY;  // a reflectance of 1 (a reradiating surface): no bound
}

}  // namespace hrad
