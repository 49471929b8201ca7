// Mean, sample variance and standard error of per-path estimates, per colour channel, accumulated
// one value at a time (Welford 1962) and merged in a fixed order (Chan, Golub & LeVeque 1979,
// "Updating formulae and a pairwise algorithm for computing sample variances"), so that blocks of
// paths run on any thread give the same bits.
#pragma once

#include <cstdint>

#include "hrad/core/types.h"

namespace hrad::detail {

struct RunningStats {
  std::uint64_t count = 0;
  Rgb mean = Rgb::Zero();
  Rgb squared_deviations = Rgb::Zero();  ///< sum of (x - mean)^2

  void add(const Rgb& x) {
    ++count;
    const Rgb delta = x - mean;
    mean += delta / static_cast<double>(count);
    squared_deviations += delta * (x - mean);
  }

  void merge(const RunningStats& o) {
    if (o.count == 0) return;
    if (count == 0) {
      *this = o;
      return;
    }
    const double n = static_cast<double>(count), m = static_cast<double>(o.count), total = n + m;
    const Rgb delta = o.mean - mean;
    mean += delta * (m / total);
    squared_deviations += o.squared_deviations + delta * delta * (n * m / total);
    count += o.count;
  }

  /// Unbiased sample variance of one estimate (0 below two samples).
  Rgb variance() const { return count > 1 ? Rgb(squared_deviations / static_cast<double>(count - 1)) : Rgb::Zero(); }
  /// Standard error of the mean: sqrt(variance / count).
  Rgb standard_error() const { return count > 0 ? Rgb((variance() / static_cast<double>(count)).sqrt()) : Rgb::Zero(); }
};

}  // namespace hrad::detail
