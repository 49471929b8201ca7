// Isolux plots of work-plane grids (render/isolux_image.h): round levels that a user can read, and
// isolines where the interpolated field crosses them.
#include "hrad/render/isolux_image.h"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "hrad/core/error.h"

namespace hrad {
namespace {

// The levels are the multiples strictly inside (lo, hi) of the smallest step {1, 2, 2.5, 5} x 10^k
// not below (hi - lo) / target, so at most `target` of them: checked against that definition over
// many ranges, and at hand-worked cases.
TEST(IsoluxLevels, AreTheRoundMultiplesOfTheSmallestStepThatFits) {
  EXPECT_EQ(isolux_levels(0, 730, 8), (std::vector<double>{100, 200, 300, 400, 500, 600, 700}));
  EXPECT_EQ(isolux_levels(312, 318, 8), (std::vector<double>{313, 314, 315, 316, 317}));
  EXPECT_EQ(isolux_levels(300, 700, 4), (std::vector<double>{400, 500, 600}));  // ends excluded
  EXPECT_EQ(isolux_levels(0, 1, 4), (std::vector<double>{0.25, 0.5, 0.75}));
  EXPECT_TRUE(isolux_levels(5, 5, 8).empty());
  EXPECT_TRUE(isolux_levels(NAN, 5, 8).empty());
  // Count of multiples of s strictly inside (lo, hi), those within 1e-6 s of an end counted as the end.
  auto inside = [](double lo, double hi, double s) {
    return std::ceil((hi - 1e-6 * s) / s) - std::floor((lo + 1e-6 * s) / s) - 1;
  };
  for (int t = 0; t < 200; ++t) {
    const double lo = std::pow(10.0, (t % 9) - 4) * (1 + 0.37 * t),
                 hi = lo + std::pow(10.0, (t % 7) - 2) * (1.3 + t % 5);
    const int target = 3 + t % 8;
    const std::vector<double> levels = isolux_levels(lo, hi, target);
    ASSERT_LE(static_cast<int>(levels.size()), target) << lo << " " << hi;
    // The smallest round step not below (hi - lo) / target.
    double step = 0;
    for (int e = -12; e <= 12 && step == 0; ++e)
      for (double m : {1.0, 2.0, 2.5, 5.0})
        if (step == 0 && m * std::pow(10.0, e) >= (hi - lo) / target) step = m * std::pow(10.0, e);
    ASSERT_GT(step, 0);
    ASSERT_LE(inside(lo, hi, step), target) << lo << " " << hi << " step " << step;
    ASSERT_EQ(static_cast<double>(levels.size()), inside(lo, hi, step)) << lo << " " << hi << " step " << step;
    for (std::size_t k = 0; k < levels.size(); ++k) {
      EXPECT_GT(levels[k], lo + 1e-7 * step);
      EXPECT_LT(levels[k], hi - 1e-7 * step);
      EXPECT_NEAR(levels[k] / step, std::round(levels[k] / step), 1e-6) << levels[k] << " step " << step;
      if (k) EXPECT_NEAR(levels[k] - levels[k - 1], step, 1e-6 * step);
    }
  }
}

// A ramp along u: cell i of an 11 x 3 grid holds 100 i, so between the outer centres the bilinear
// field is 100 (11 u - 1/2) at u in [0, 1] across the plot, and the isoline of level L lies at
// u = (L / 100 + 1/2) / 11. On every row the dark isoline pixels are within one pixel of there, the
// bands between them are one colour each, in ascending order of the colour map, and the colour bar
// (right of the plot) shows one block per band.
TEST(IsoluxImage, IsolinesOfARampLieWhereItCrossesTheLevels) {
  const int nu = 11, nv = 3;
  std::vector<double> values;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) values.push_back(100.0 * i);
  IsoluxOptions o;
  o.long_side = 440;
  o.aspect = 4.0;
  o.unit = "lx";
  const IsoluxImage plot = render_isolux(values, nu, nv, o);
  ASSERT_EQ(plot.levels, (std::vector<double>{200, 400, 600, 800}));  // 0..1000, at most 8: step 200
  ASSERT_EQ(plot.plot_width, 440);
  ASSERT_EQ(plot.image.height, 110);
  ASSERT_GT(plot.image.width, 440);
  const Rgb8 ink{20, 20, 20};
  for (int y = 0; y < plot.image.height; ++y) {
    std::vector<int> lines;
    for (int x = 0; x < plot.plot_width; ++x)
      if (plot.image.at(x, y) == ink) lines.push_back(x);
    ASSERT_EQ(lines.size(), 4u) << "row " << y;
    for (std::size_t k = 0; k < 4; ++k) {
      const double u = (plot.levels[k] / 100.0 + 0.5) / nu, px = u * plot.plot_width - 0.5;
      EXPECT_LE(std::abs(lines[k] - px), 1.0) << "row " << y << " level " << plot.levels[k];
    }
    // Band colours: constant between lines, distinct, ordered as the map.
    for (std::size_t k = 0; k <= 4; ++k) {
      const int x0 = k == 0 ? 0 : lines[k - 1] + 1, x1 = k == 4 ? plot.plot_width : lines[k];
      for (int x = x0; x < x1; ++x) EXPECT_EQ(plot.image.at(x, y), sequential_colormap((k + 0.5) / 5)) << x << "," << y;
    }
  }
  std::set<Rgb8> bar;
  for (int y = 0; y < plot.image.height; ++y) bar.insert(plot.image.at(plot.plot_width + 10, y));
  for (int k = 0; k < 5; ++k) EXPECT_EQ(bar.count(sequential_colormap((k + 0.5) / 5)), 1u) << k;
}

// A ramp along v (row j holds 100 j): v runs up the plot, or down with v_down; the lowest band is
// at the bottom, or at the top.
TEST(IsoluxImage, VRunsUpOrDown) {
  std::vector<double> values;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 2; ++i) values.push_back(100.0 * j);
  IsoluxOptions o;
  o.long_side = 100;
  const IsoluxImage up = render_isolux(values, 2, 5, o);
  o.v_down = true;
  const IsoluxImage down = render_isolux(values, 2, 5, o);
  ASSERT_EQ(up.levels, down.levels);
  const int bands = static_cast<int>(up.levels.size()) + 1;
  const Rgb8 lowest = sequential_colormap(0.5 / bands), highest = sequential_colormap((bands - 0.5) / bands);
  EXPECT_EQ(up.image.at(50, 99), lowest);
  EXPECT_EQ(up.image.at(50, 0), highest);
  EXPECT_EQ(down.image.at(50, 0), lowest);
  EXPECT_EQ(down.image.at(50, 99), highest);
}

TEST(IsoluxImage, BadGridsAreErrors) {
  const std::vector<double> v(6, 1.0);
  EXPECT_THROW(render_isolux(v, 2, 2), Error);
  IsoluxOptions o;
  o.aspect = 0;
  EXPECT_THROW(render_isolux(v, 3, 2, o), Error);
  // A uniform field has no level: one band, no isoline.
  const IsoluxImage flat = render_isolux(v, 3, 2);
  EXPECT_TRUE(flat.levels.empty());
  EXPECT_EQ(flat.image.at(10, 10), sequential_colormap(0.5));
}

}  // namespace
}  // namespace hrad
