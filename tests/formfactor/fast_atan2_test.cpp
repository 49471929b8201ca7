// fast_atan2 against long double atan2l over all octants and 24 decades of argument ratio.
#include "hrad/formfactor/fast_atan2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace hrad::detail {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

TEST(FastAtan2, WithinAnUlpOfLongDoubleAtan2) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0), decade(-12.0, 12.0);
  double worst = 0.0;
  for (int i = 0; i < 2'000'000; ++i) {
    const double y = std::abs(u(rng)) * std::pow(10.0, decade(rng));
    const double x = u(rng) * std::pow(10.0, decade(rng));
    const long double exact = atan2l(static_cast<long double>(y), static_cast<long double>(x));
    if (exact == 0.0L) continue;
    const double error = static_cast<double>(std::abs((fast_atan2(y, x) - exact) / exact));
    worst = std::max(worst, error);
  }
  // ~1 ulp: the library's atan2 is within 1 ulp as well (a double's ulp is between eps/2 and eps
  // of its value).
  EXPECT_LE(worst, 1.25 * kEps);
  EXPECT_GT(worst, 0.0);  // the comparison is not against itself
}

TEST(FastAtan2, TableBoundariesAndSpecialValues) {
  EXPECT_EQ(fast_atan2(0.0, 1.0), 0.0);
  EXPECT_EQ(fast_atan2(0.0, 0.0), 0.0);
  EXPECT_EQ(fast_atan2(0.0, -2.0), std::numbers::pi);
  EXPECT_EQ(fast_atan2(3.0, 0.0), std::numbers::pi / 2);
  EXPECT_EQ(fast_atan2(1.0, 1.0), std::numbers::pi / 4);
  EXPECT_EQ(fast_atan2(1.0, -1.0), 3 * std::numbers::pi / 4);
  // Around each reduction point k/16 and the switch to c = 0 at 3/32, on both sides.
  for (int k = 0; k <= 32; ++k)
    for (double d : {-1e-12, -1e-16, 0.0, 1e-16, 1e-12}) {
      const double t = k / 32.0 + d;
      if (t < 0.0 || t > 1.0) continue;
      for (const auto& [y, x] : {std::pair{t, 1.0}, std::pair{1.0, t}, std::pair{t, -1.0}, std::pair{1.0, -t}}) {
        const long double exact = atan2l(y, x);
        if (exact == 0.0L) continue;
        EXPECT_LE(static_cast<double>(std::abs((fast_atan2(y, x) - exact) / exact)), 1.25 * kEps) << y << " " << x;
      }
    }
}

}  // namespace
}  // namespace hrad::detail
