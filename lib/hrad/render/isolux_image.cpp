#include "hrad/render/isolux_image.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/render/render.h"

namespace hrad {

std::vector<double> isolux_levels(double lo, double hi, int target) {
  std::vector<double> levels;
  if (!(std::isfinite(lo) && std::isfinite(hi) && hi > lo) || target < 1) return levels;
  const double raw = (hi - lo) / target;
  double step = 0.0;
  for (int e = static_cast<int>(std::floor(std::log10(raw))); step == 0.0; ++e)
    for (double m : {1.0, 2.0, 2.5, 5.0})
      if (m * std::pow(10.0, e) >= raw && step == 0.0) step = m * std::pow(10.0, e);
  // A step of at least (hi - lo) / target leaves at most `target` multiples strictly inside.
  // Multiples within 1e-6 step of an end count as the end (lo / step rounds: 61.8 / 0.01 < 6180).
  const double margin = 1e-6 * step, first = std::floor((lo + margin) / step) + 1.0;
  for (int n = 0; n <= target; ++n) {
    const double level = (first + n) * step;
    if (level >= hi - margin) break;
    levels.push_back(level);
  }
  return levels;
}

Rgb8 sequential_colormap(double t) {
  static constexpr std::array<std::array<double, 3>, 5> anchors = {
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  t = std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0) * (anchors.size() - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(t), anchors.size() - 2);
  const double f = t - static_cast<double>(i);
  Rgb8 c;
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<std::uint8_t>(std::lround(anchors[i][k] + f * (anchors[i + 1][k] - anchors[i][k])));
  return c;
}

IsoluxImage render_isolux(std::span<const double> values, int nu, int nv, const IsoluxOptions& o) {
  if (nu < 1 || nv < 1 || values.size() != static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv))
    throw Error(fmt::format("isolux image: {} values for a {} x {} grid", values.size(), nu, nv));
  if (!(o.long_side >= 16 && o.long_side <= 16384))
    throw Error(fmt::format("isolux image: size {} not in [16, 16384]", o.long_side));
  if (!(o.aspect > 0 && std::isfinite(o.aspect)))
    throw Error(fmt::format("isolux image: aspect {} is not > 0", o.aspect));
  const int w = o.aspect >= 1 ? o.long_side : std::max(1, static_cast<int>(std::lround(o.long_side * o.aspect)));
  const int h = o.aspect >= 1 ? std::max(1, static_cast<int>(std::lround(o.long_side / o.aspect))) : o.long_side;
  double lo = INFINITY, hi = -INFINITY;
  for (double v : values)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  IsoluxImage out;
  out.levels = isolux_levels(lo, hi, o.target_levels);
  const std::vector<double>& levels = out.levels;
  const int bands = static_cast<int>(levels.size()) + 1;
  auto band_of = [&](double v) {
    return static_cast<int>(std::upper_bound(levels.begin(), levels.end(), v) - levels.begin());
  };
  auto band_colour = [&](int b) { return sequential_colormap(bands > 1 ? (b + 0.5) / bands : 0.5); };
  auto value = [&](int i, int j) { return values[static_cast<std::size_t>(j) * nu + i]; };

  // The interpolated value's band at each pixel centre (u right, v up or down).
  std::vector<int> band(static_cast<std::size_t>(w) * h);
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const double gu = std::clamp((px + 0.5) / w * nu - 0.5, 0.0, nu - 1.0);
      const double down = (py + 0.5) / h;
      const double gv = std::clamp((o.v_down ? down : 1.0 - down) * nv - 0.5, 0.0, nv - 1.0);
      const int i = std::min(static_cast<int>(gu), std::max(0, nu - 2));
      const int j = std::min(static_cast<int>(gv), std::max(0, nv - 2));
      const int i1 = std::min(i + 1, nu - 1), j1 = std::min(j + 1, nv - 1);
      const double fu = gu - i, fv = gv - j;
      const double v =
          (1 - fv) * ((1 - fu) * value(i, j) + fu * value(i1, j)) + fv * ((1 - fu) * value(i, j1) + fu * value(i1, j1));
      band[static_cast<std::size_t>(py) * w + px] = band_of(v);
    }

  const int scale = std::max(1, h / 256);
  const std::string widest = levels.empty() ? std::string("0") : fmt::format("{:g}", levels.back());
  const int label_chars = static_cast<int>(widest.size() + (o.unit.empty() ? 0 : o.unit.size() + 1));
  const int strip = 12 * scale + 8 * scale + 4 * scale * label_chars + 8 * scale;
  out.plot_width = w;
  out.image = Image(w + strip, h, Rgb8{255, 255, 255});
  Image& image = out.image;
  const Rgb8 ink{20, 20, 20};
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const int b = band[static_cast<std::size_t>(py) * w + px];
      const bool edge = (px + 1 < w && band[static_cast<std::size_t>(py) * w + px + 1] != b) ||
                        (py + 1 < h && band[static_cast<std::size_t>(py + 1) * w + px] != b);
      image.at(px, py) = edge ? ink : band_colour(b);
    }
  // The colour bar: one block per band, band 0 at the bottom, each level labelled at its boundary.
  const int bar_x0 = w + 8 * scale, bar_x1 = bar_x0 + 12 * scale;
  const int bar_y0 = 8 * scale, bar_y1 = h - 8 * scale;
  const double block = static_cast<double>(bar_y1 - bar_y0) / bands;
  for (int y = bar_y0; y < bar_y1; ++y) {
    const int b = std::min(bands - 1, static_cast<int>((bar_y1 - 1 - y) / block));
    for (int x = bar_x0; x < bar_x1; ++x) image.at(x, y) = band_colour(b);
  }
  const int label_step = std::max(1, static_cast<int>(std::ceil(8.0 * scale / block)));  // labels 8 px apart at least
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const int y = bar_y1 - static_cast<int>(std::lround((k + 1) * block));
    for (int x = bar_x0; x < bar_x1 + 3 * scale; ++x) image.at(x, y) = ink;
    if (k % static_cast<std::size_t>(label_step) != 0) continue;
    const std::string label = fmt::format("{:g}", levels[k]) + (o.unit.empty() ? "" : " " + o.unit);
    draw_text(image, bar_x1 + 5 * scale, y - 2 * scale, label, ink, scale);
  }
  return out;
}

}  // namespace hrad
