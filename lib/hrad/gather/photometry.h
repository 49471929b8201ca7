// Photometric values from a solution's RGB light, for lighting designers: illuminance in lux.
// hrad's radiosity, emission and irradiance are in whatever exitance units the scene's emission
// (MTL Ke) is in; the scene declares which (README "Scene format") or the user does
// (`hrad probe --emission-units`):
//   * lm/m2: each emission's luminance-weighted sum (below) is its luminous exitance in lm/m^2, so a
//     grey Ke of (k, k, k) emits k lm/m^2 and an irradiance's weighted sum is its illuminance in lux;
//   * W/m2: each channel is radiant exitance in W/m^2 of (equal-energy) white light, and the weighted
//     sum times the luminous efficacy of white light, 179 lm/W, is in lumens.
// The weights are the luminance of the RGB primaries, and 179 lm/W the efficacy, of the Radiance
// lighting simulation system (Ward 1994, "The RADIANCE Lighting Simulation and Rendering System",
// SIGGRAPH; its `bright()` and WHTEFFICACY, as rtrace -i and rlux use them):
//   lux = efficacy * (0.265074126 R + 0.670114631 G + 0.064811243 B).
// The weights sum to 1, so grey light is the same number in every channel and in lux (lm/m2).
#pragma once

#include "hrad/core/emission_units.h"
#include "hrad/core/types.h"

namespace hrad {

/// Lumens per unit of the luminance-weighted value: 1 (lm/m2) or 179 (W/m2, white light).
double luminous_efficacy(EmissionUnits units);

/// The luminance-weighted sum of an RGB value (weights above, summing to 1).
double luminance_weighted(const Rgb& value);

/// Illuminance in lux of an irradiance in the declared units.
inline double illuminance_lux(const Rgb& irradiance, EmissionUnits units) {
  return luminous_efficacy(units) * luminance_weighted(irradiance);
}

}  // namespace hrad
