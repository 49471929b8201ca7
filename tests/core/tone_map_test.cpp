#include "hrad/core/tone_map.h"

#include <cmath>

#include <gtest/gtest.h>

namespace hrad {
namespace {

TEST(ToneMap, SrgbCurveAtKnownPoints) {
  EXPECT_EQ(srgb_encode(0.0), 0.0);
  EXPECT_NEAR(srgb_encode(1.0), 1.0, 1e-12);
  EXPECT_NEAR(srgb_encode(0.002), 12.92 * 0.002, 1e-15);  // linear segment
  EXPECT_NEAR(srgb_encode(0.18), 0.4613561295, 1e-9);     // 1.055*0.18^(1/2.4)-0.055
  // The two pieces meet (continuity at the breakpoint, to 1e-4 as in the standard).
  EXPECT_NEAR(12.92 * 0.0031308, 1.055 * std::pow(0.0031308, 1 / 2.4) - 0.055, 1e-4);
}

TEST(ToneMap, ExposureScalesThenClamps) {
  // 0.09 * 2 = 0.18 -> 0.46136 -> round(117.65) = 118.
  EXPECT_EQ(tone_map(Rgb(0.09, 0.0, 5.0), 2.0), (Rgb8{118, 0, 255}));
  EXPECT_EQ(tone_map(Rgb(-1.0, 1.0, 0.5), 1.0), (Rgb8{0, 255, 188}));
  EXPECT_EQ(tone_map(Rgb(NAN, 0.0, 0.0), 1.0), (Rgb8{0, 0, 0}));
}

Solution strip(const std::vector<double>& luminances, const std::vector<double>& widths) {
  // Unit-height rectangles side by side along x, grey radiosity = luminance (R=G=B).
  Solution s;
  double x = 0.0;
  for (std::size_t i = 0; i < luminances.size(); ++i) {
    const int b = static_cast<int>(s.vertices.size());
    s.vertices.insert(s.vertices.end(),
                      {Vec3(x, 0, 0), Vec3(x + widths[i], 0, 0), Vec3(x + widths[i], 1, 0), Vec3(x, 1, 0)});
    s.vertex_radiosity.insert(s.vertex_radiosity.end(), 4, Rgb::Constant(luminances[i]));
    s.faces.push_back({b, b + 1, b + 2, b + 3});
    s.face_patch.push_back(static_cast<int>(i));
    s.face_radiosity.push_back(Rgb::Constant(luminances[i]));
    x += widths[i];
  }
  return s;
}

TEST(ToneMap, AutoExposureUsesAreaWeightedPercentile) {
  // 96% of the area has luminance 0.5, 4% is a bright light of 100: the 95th percentile is 0.5.
  const Solution s = strip({0.5, 100.0}, {0.96, 0.04});
  EXPECT_NEAR(auto_exposure(s), 0.8 / 0.5, 1e-12);
  // With the light covering 10% of the area, it is the 95th percentile unless excluded.
  const Solution t = strip({0.5, 100.0}, {0.9, 0.1});
  EXPECT_NEAR(auto_exposure(t), 0.8 / 100.0, 1e-12);
  EXPECT_NEAR(auto_exposure(t, {false, true}), 0.8 / 0.5, 1e-12);
  EXPECT_EQ(auto_exposure(strip({0.0}, {1.0})), 1.0);
}

}  // namespace
}  // namespace hrad
