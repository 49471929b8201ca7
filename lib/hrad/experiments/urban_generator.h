// Urban scale scenes for view factors: blocks of box buildings on a ground, meshed like city
// models are (non-watertight: the ground runs on under the buildings, walls stand on it in
// T-junctions, no building has a floor, neighbours may share a wall plane). Deterministic in a seed.
//
// Layout: a g x g grid of 80 m blocks (60 m of land, 20 m of street), each with up to four
// buildings of random footprint (12..26 m) and height (6..45 m); the ground is tiled with 10 m
// quads facing up; walls and roofs are cut into quads of one size chosen so that the total comes
// to about the requested count.
#pragma once

#include <cstdint>

#include "hrad/experiments/scene_generator.h"

namespace hrad {

struct UrbanGeneratorOptions {
  int facets = 22000;  ///< requested facets (>= 200)
  std::uint64_t seed = 1;
};

/// Materials: 0 ground (reflectance 0.1), 1 walls (0.3), 2 roofs (0.2); groups "ground",
/// "building<k>". hrad::Error naming --polygons outside [200, 10,000,000].
GeneratedScene generate_urban(const UrbanGeneratorOptions& options);

}  // namespace hrad
