#include "hrad/analysis/power_law_fit.h"

#include <cmath>
#include <limits>

#include <ceres/ceres.h>
#include <fmt/format.h>

#include "hrad/core/error.h"

namespace hrad {
namespace {

struct LogResidual {
  LogResidual(double log_x, double log_y, double sqrt_w) : log_x(log_x), log_y(log_y), sqrt_w(sqrt_w) {}
  template <class T>
  bool operator()(const T* log_a, const T* b, T* residual) const {
    residual[0] = T(sqrt_w) * (T(log_y) - log_a[0] - b[0] * T(log_x));
    return true;
  }
  double log_x, log_y, sqrt_w;
};

}  // namespace

double PowerLawFit::predict(double x) const { return a * std::pow(x, b); }

PowerLawFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y,
                          const std::vector<double>& weights) {
  if (x.size() != y.size()) throw Error(fmt::format("power-law fit: {} x values but {} y values", x.size(), y.size()));
  if (!weights.empty() && weights.size() != x.size())
    throw Error(fmt::format("power-law fit: {} weights for {} points", weights.size(), x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0.0 && std::isfinite(x[i])))
      throw Error(fmt::format("power-law fit: x[{}] = {} is not positive", i, x[i]));
    if (!(y[i] > 0.0 && std::isfinite(y[i])))
      throw Error(fmt::format("power-law fit: y[{}] = {} is not positive", i, y[i]));
    if (!weights.empty() && !(weights[i] > 0.0 && std::isfinite(weights[i])))
      throw Error(fmt::format("power-law fit: weight[{}] = {} is not positive", i, weights[i]));
  }
  bool distinct = false;
  for (std::size_t i = 1; i < x.size(); ++i) distinct = distinct || x[i] != x[0];
  if (!distinct) throw Error("power-law fit: needs at least two distinct x values");

  // Start from the flat line through the first point (ln a = ln y[0], b = 0): the residuals are
  // linear in (ln a, b), so Ceres's first Gauss-Newton step reaches the minimum from any start;
  // Ceres is used for the covariance it also gives.
  double params[2] = {std::log(y[0]), 0.0};  // ln a, b
  ceres::Problem problem;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<LogResidual, 1, 1, 1>(
                                 new LogResidual(std::log(x[i]), std::log(y[i]), std::sqrt(w))),
                             nullptr, &params[0], &params[1]);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.function_tolerance = 1e-15;
  options.gradient_tolerance = 1e-15;
  options.parameter_tolerance = 1e-15;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  PowerLawFit fit;
  fit.points = static_cast<int>(x.size());
  fit.converged = summary.IsSolutionUsable();
  if (!fit.converged) fit.message = summary.BriefReport();
  fit.log_a = params[0];
  fit.b = params[1];
  fit.a = std::exp(params[0]);

  double rss = 0.0, wsum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    const double r = std::log(y[i]) - params[0] - params[1] * std::log(x[i]);
    rss += w * r * r;
    wsum += w;
  }
  fit.rms_log_residual = std::sqrt(rss / wsum);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  fit.a_stderr = fit.b_stderr = fit.log_a_stderr = fit.covariance_log_a_b = nan;
  if (x.size() > 2) {
    ceres::Covariance::Options cov_options;
    ceres::Covariance covariance(cov_options);
    std::vector<std::pair<const double*, const double*>> blocks = {
        {&params[0], &params[0]}, {&params[1], &params[1]}, {&params[0], &params[1]}};
    if (covariance.Compute(blocks, &problem)) {
      const double s2 = rss / static_cast<double>(x.size() - 2);
      double caa = 0.0, cbb = 0.0, cab = 0.0;
      covariance.GetCovarianceBlock(&params[0], &params[0], &caa);
      covariance.GetCovarianceBlock(&params[1], &params[1], &cbb);
      covariance.GetCovarianceBlock(&params[0], &params[1], &cab);
      fit.log_a_stderr = std::sqrt(s2 * caa);
      fit.b_stderr = std::sqrt(s2 * cbb);
      fit.covariance_log_a_b = s2 * cab;
      fit.a_stderr = fit.a * fit.log_a_stderr;
    }
  }
  return fit;
}

}  // namespace hrad
