// Images, row-major from the top-left pixel: 8-bit RGB for display, linear RGB for HDR files.
#pragma once

#include <vector>

#include "hrad/core/tone_map.h"

namespace hrad {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<Rgb8> pixels;  ///< width * height, row y at [y * width, (y + 1) * width)

  Image() = default;
  Image(int w, int h, Rgb8 fill = {0, 0, 0}) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, fill) {}
  Rgb8& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const Rgb8& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

/// Linear RGB per pixel (radiosity, irradiance, ...), for HDR files.
struct HdrImage {
  int width = 0;
  int height = 0;
  std::vector<Rgb> pixels;  ///< width * height, row y at [y * width, (y + 1) * width)

  HdrImage() = default;
  HdrImage(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h, Rgb::Zero()) {}
  Rgb& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const Rgb& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

}  // namespace hrad
