#include "hrad/core/tone_map.h"

#include <algorithm>
#include <cmath>

#include "hrad/core/face_geometry.h"

namespace hrad {

double srgb_encode(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

double srgb_decode(double encoded) {
  const double v = std::clamp(encoded, 0.0, 1.0);
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

Rgb8 tone_map(const Rgb& radiosity, double exposure) {
  Rgb8 out{};
  for (int c = 0; c < 3; ++c) {
    const double x = std::isfinite(radiosity[c]) ? exposure * radiosity[c] : 0.0;
    out[c] = static_cast<std::uint8_t>(std::lround(255.0 * srgb_encode(x)));
  }
  return out;
}

double luminance(const Rgb& rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

double auto_exposure(const Solution& solution, const std::vector<bool>& exclude_patch) {
  struct Sample {
    double luminance, area;
  };
  std::vector<Sample> samples;
  double total = 0.0;
  for (std::size_t f = 0; f < solution.faces.size(); ++f) {
    const int p = f < solution.face_patch.size() ? solution.face_patch[f] : -1;
    if (p >= 0 && static_cast<std::size_t>(p) < exclude_patch.size() && exclude_patch[p]) continue;
    const double a = face_area(solution, f);
    if (!(a > 0.0)) continue;
    samples.push_back({luminance(solution.face_radiosity[f]), a});
    total += a;
  }
  if (samples.empty()) return 1.0;
  std::sort(samples.begin(), samples.end(), [](const Sample& x, const Sample& y) { return x.luminance < y.luminance; });
  double acc = 0.0;
  double l95 = samples.back().luminance;
  for (const Sample& s : samples) {
    acc += s.area;
    if (acc >= 0.95 * total) {
      l95 = s.luminance;
      break;
    }
  }
  return l95 > 0.0 ? 0.8 / l95 : 1.0;
}

}  // namespace hrad
