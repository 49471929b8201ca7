// Where a pixel is sampled for antialiasing: stratified jittered points (Cook 1986, "Stochastic
// sampling in computer graphics"), one per pass, fixed by the pixel, the pass and a seed, so that
// an image is the same whatever order or thread computes it.
#pragma once

#include <cstdint>

#include "hrad/core/types.h"

namespace hrad {

/// Sample `pass` of `passes` (>= 1) in pixel (x, y), in pixel coordinates (inside [x, x+1) x
/// [y, y+1)). With passes = m^2, pass k lies uniformly in cell (k mod m, k div m) of an m x m grid
/// over the pixel; otherwise in column k of `passes` columns and in row pi(k) of as many rows, pi a
/// random permutation per pixel (N-rooks; Shirley 1991): both are stratified in x and in y.
Vec2 pixel_sample(int x, int y, int pass, int passes, std::uint64_t seed);

}  // namespace hrad
