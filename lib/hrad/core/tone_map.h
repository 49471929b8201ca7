// Display of linear radiosity: exposure, clamp, sRGB transfer curve. One function used by the
// PLY vertex colours and every rendered image, so that they agree.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "hrad/core/solution.h"
#include "hrad/core/types.h"

namespace hrad {

using Rgb8 = std::array<std::uint8_t, 3>;

/// Linear value v -> sRGB-encoded value in [0, 1]: 12.92 v below 0.0031308, else
/// 1.055 v^(1/2.4) - 0.055 (IEC 61966-2-1). v is clamped to [0, 1] first.
double srgb_encode(double linear);

/// The inverse of srgb_encode on [0, 1]: v / 12.92 below 0.04045, else ((v + 0.055) / 1.055)^2.4.
double srgb_decode(double encoded);

/// Each channel: x = clamp(exposure * radiosity, 0, 1), then srgb_encode, then round(255 x).
Rgb8 tone_map(const Rgb& radiosity, double exposure);

/// Rec. 709 luminance 0.2126 R + 0.7152 G + 0.0722 B of a linear RGB triple.
double luminance(const Rgb& rgb);

/// An exposure that maps the 95th percentile of the area-weighted luminance distribution of the
/// leaf elements to 0.8 (so most surfaces are not clipped; bright light sources may be).
/// Faces whose patch p has `exclude_patch[p]` true (e.g. emitters) are left out; an empty vector
/// excludes nothing. Returns 1 when every considered face is black.
double auto_exposure(const Solution& solution, const std::vector<bool>& exclude_patch = {});

}  // namespace hrad
