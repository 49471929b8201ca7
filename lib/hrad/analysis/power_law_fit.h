// Fits of y ~ a x^b (cost ~ a n^b, links ~ c n^alpha, error ~ k eps^beta) with Ceres.
//
// Model: least squares in log space, minimising sum_i w_i (ln y_i - ln a - b ln x_i)^2, i.e. a
// multiplicative (log-normal) error model in which every point has the same relative scatter.
// Standard errors: the covariance of (ln a, b) is s^2 (J^T W J)^-1 (ceres::Covariance gives
// (J^T J)^-1 of the weighted residuals) with s^2 = (weighted residual sum of squares) / (n - 2),
// the usual unbiased estimate when the scatter is not known in advance; se(a) = a se(ln a) (delta
// method). With n = 2 the fit is exact and the standard errors are NaN.
#pragma once

#include <string>
#include <vector>

namespace hrad {

struct PowerLawFit {
  double a = 0.0, b = 0.0;                 ///< y ~ a x^b
  double a_stderr = 0.0, b_stderr = 0.0;   ///< one standard error
  double log_a = 0.0, log_a_stderr = 0.0;  ///< ln a and its standard error
  double covariance_log_a_b = 0.0;
  double rms_log_residual = 0.0;  ///< sqrt(weighted RSS / sum w), in ln units
  int points = 0;
  bool converged = false;
  std::string message;  ///< Ceres' report when not converged

  double predict(double x) const;
};

/// Fits y ~ a x^b. x and y must be positive and finite, with at least two distinct x; `weights`
/// (empty = all 1) must be positive. Bad input is an hrad::Error naming the offending index.
PowerLawFit fit_power_law(const std::vector<double>& x, const std::vector<double>& y,
                          const std::vector<double>& weights = {});

}  // namespace hrad
