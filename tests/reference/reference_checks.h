// Helpers for the reference's tests: agreement with a closed form in standard errors.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "hrad/core/types.h"

namespace hrad::test {

/// Each channel of `value` within `sigmas` standard errors `se` of `expected`, and each standard
/// error at most `max_relative_se` of the expected value (so that the bound means something).
inline void expect_agrees(const Rgb& value, const Rgb& se, const Rgb& expected, double max_relative_se,
                          const std::string& what, double sigmas = 4.0) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_LE(std::abs(value[c] - expected[c]), sigmas * se[c])
        << what << " channel " << c << ": " << value[c] << " +- " << se[c] << " against " << expected[c] << " ("
        << (value[c] - expected[c]) / se[c] << " standard errors)";
    EXPECT_LE(se[c], max_relative_se * std::abs(expected[c]))
        << what << " channel " << c << ": standard error " << se[c] << " too large to test " << expected[c];
  }
}

}  // namespace hrad::test
