// An image of a solution by final gather: each pixel's samples see a point of a leaf (the
// rasterizer's nearest polygon at a jittered point of the pixel, the hit point exact on the leaf's
// plane), and each point's radiosity is gathered there, B(x) = E + rho H(x) (final_gather.h), not
// read from the elements. The samples are averaged as PixelAverager does (render.h): a display
// image with the same exposure rule as the Gouraud one and a linear one for HDR files.
#pragma once

#include <cstdint>

#include "hrad/core/image.h"
#include "hrad/core/solution.h"
#include "hrad/gather/final_gather.h"
#include "hrad/render/render.h"

namespace hrad {

struct GatheredImage {
  Image display;           ///< tone-mapped (RenderOptions::exposure), antialiased
  HdrImage radiosity;      ///< mean gathered radiosity B over each pixel's samples (0 where a sample saw nothing)
  std::size_t points = 0;  ///< samples gathered (those that saw a leaf)
  double seconds = 0.0;    ///< the whole image: rasterizing, gathering, averaging
  double gather_seconds = 0.0;
  GatherWork work;  ///< this image's share of the gather's work
};

/// Renders `solution` (the leaves `gather` gathers from, on `gather.scene()`) with
/// options.samples_per_pixel jittered samples per pixel. Deterministic (the gather is, and each
/// pixel's samples are summed in pass order). Progress: options.progress, per point gathered.
GatheredImage render_gathered(const Solution& solution, const FinalGather& gather, const RenderOptions& options);

}  // namespace hrad
