#include "hrad/formfactor/gauss_legendre.h"

#include <array>
#include <cassert>
#include <cmath>
#include <numbers>
#include <vector>

namespace hrad::detail {
namespace {

struct Table {
  std::array<std::vector<double>, kMaxGaussOrder + 1> nodes, weights;
  Table() {
    for (int n = 1; n <= kMaxGaussOrder; ++n) {
      std::vector<double> x(n), w(n);
      for (int i = 0; i < (n + 1) / 2; ++i) {
        // Initial guess (Tricomi), then Newton on P_n(z) with P_n' from the recurrence.
        double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double dp = 1.0;
        for (int it = 0; it < 20; ++it) {
          double p0 = 1.0, p1 = z;
          if (n == 1) p0 = 1.0;
          for (int k = 2; k <= n; ++k) {
            const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
            p0 = p1;
            p1 = p2;
          }
          // p1 = P_n(z), p0 = P_{n-1}(z)
          dp = n * (z * p1 - p0) / (z * z - 1.0);
          const double dz = p1 / dp;
          z -= dz;
          if (std::abs(dz) < 1e-15) break;  // quadratic convergence: this step brought z to rounding
        }
        {
          double p0 = 1.0, p1 = z;
          for (int k = 2; k <= n; ++k) {
            const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
            p0 = p1;
            p1 = p2;
          }
          dp = n * (z * p1 - p0) / (z * z - 1.0);
        }
        const double wi = 2.0 / ((1.0 - z * z) * dp * dp);
        x[i] = -z;
        x[n - 1 - i] = z;
        w[i] = w[n - 1 - i] = wi;
      }
      if (n % 2 == 1) x[n / 2] = 0.0;
      nodes[n] = std::move(x);
      weights[n] = std::move(w);
    }
  }
};

}  // namespace

GaussRule gauss_legendre(int n) {
  assert(n >= 1 && n <= kMaxGaussOrder);
  static const Table table;
  return {table.nodes[n], table.weights[n]};
}

}  // namespace hrad::detail
