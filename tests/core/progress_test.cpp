// The progress reporter's arithmetic (time left, iterations left) and its rate limit, on a clock the
// test drives, so nothing here depends on how loaded the machine is.
#include "hrad/core/progress.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace hrad {
namespace {

TEST(Eta, LinearRateSoFarTimesUnitsLeft) {
  // 25 of 100 units in 10 s: 0.4 s per unit, 75 left -> 30 s.
  EXPECT_DOUBLE_EQ(*eta_seconds(25, 100, 10.0), 30.0);
  // 1 of 3 in 2 s -> 4 s; all done -> 0; past the total (a loose total) -> 0.
  EXPECT_DOUBLE_EQ(*eta_seconds(1, 3, 2.0), 4.0);
  EXPECT_DOUBLE_EQ(*eta_seconds(100, 100, 7.0), 0.0);
  EXPECT_DOUBLE_EQ(*eta_seconds(120, 100, 7.0), 0.0);
  // Nothing done yet: no rate, no estimate (not 0, not infinity).
  EXPECT_FALSE(eta_seconds(0, 100, 5.0).has_value());
  EXPECT_FALSE(eta_seconds(5, 100, NAN).has_value());
  // Large counts do not overflow: 1e12 of 4e12 pairs in 1000 s -> 3000 s.
  EXPECT_DOUBLE_EQ(*eta_seconds(1'000'000'000'000ULL, 4'000'000'000'000ULL, 1000.0), 3000.0);
}

TEST(IterationsLeft, GeometricExtrapolationOfTheChange) {
  // The change fell from 1e-2 to 1e-3 over 10 iterations: a factor 10 per 10 iterations, so 1e-6
  // needs 30 more.
  EXPECT_DOUBLE_EQ(*iterations_left(1e-2, 1e-3, 10, 1e-6), 30.0);
  // Halving each iteration from 1 to 0.5: 1e-3 needs ceil(log2(500)) = 9 more (0.5 / 2^9 < 1e-3 <= 0.5 / 2^8).
  EXPECT_DOUBLE_EQ(*iterations_left(1.0, 0.5, 1, 1e-3), 9.0);
  EXPECT_DOUBLE_EQ(*iterations_left(1.0, 1e-7, 3, 1e-6), 0.0);
  // No decrease, no estimate.
  EXPECT_FALSE(iterations_left(1e-3, 1e-3, 5, 1e-6).has_value());
  EXPECT_FALSE(iterations_left(1e-3, 2e-3, 5, 1e-6).has_value());
  EXPECT_FALSE(iterations_left(NAN, 1e-3, 5, 1e-6).has_value());
}

TEST(FormatDuration, ReadableUnits) {
  EXPECT_EQ(format_duration(4.24), "4.2 s");
  EXPECT_EQ(format_duration(185.0), "3 min 05 s");
  EXPECT_EQ(format_duration(2 * 3600 + 7 * 60 + 20), "2 h 07 min");
  EXPECT_EQ(format_duration(-1.0), "?");
  EXPECT_EQ(format_count(0), "0");
  EXPECT_EQ(format_count(999), "999");
  EXPECT_EQ(format_count(1000), "1,000");
  EXPECT_EQ(format_count(12345678), "12,345,678");
}

TEST(ProgressLine, CountsPercentElapsedAndTimeLeft) {
  EXPECT_EQ(progress_line("form factors", 250, 1000, "pairs", 10.0),
            "form factors: 250 / 1,000 pairs (25%), 10.0 s, about 30.0 s left");
  EXPECT_EQ(progress_line("render", 10, 10, "rows", 3.0), "render: 10 / 10 rows (100%), 3.0 s");
}

// The reporter prints at most one line per interval on its clock, none for work shorter than one
// interval, and a closing line only after it printed something.
TEST(ProgressReporter, RateLimitedLinesWithTheRightCounts) {
  double t = 0.0;
  std::vector<std::string> lines;
  {
    ProgressReporter p(
        "work", 100, "items", [&](std::string_view l) { lines.emplace_back(l); }, 2.0, [&] { return t; });
    for (int i = 0; i < 100; ++i) {
      t = i / 10.0;  // 10 s for 100 items
      p.advance();
    }
    p.finish();
    p.finish();
  }
  // Lines at t >= 2, 4, 6, 8 (the first advance at or after each due time), then the closing line.
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0], "work: 21 / 100 items (21%), 2.0 s, about 7.5 s left");  // at t = 2.0 with 21 done
  EXPECT_EQ(lines[4], "work: done, 100 items in 9.9 s");

  lines.clear();
  ProgressReporter quick(
      "quick", 10, "items", [&](std::string_view l) { lines.emplace_back(l); }, 2.0, [&] { return 0.5; });
  quick.advance(10);
  quick.finish();
  EXPECT_TRUE(lines.empty());
}

}  // namespace
}  // namespace hrad
