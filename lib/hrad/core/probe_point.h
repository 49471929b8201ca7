// A point where a user asks for light: a position and the direction its sensor faces (a lighting
// designer's probe). Read by io/ (read_points_csv), answered by the Monte Carlo reference.
#pragma once

#include <cstddef>

#include "hrad/core/types.h"

namespace hrad {

struct ProbePoint {
  Vec3 position = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  ///< unit vector: the side the probe receives light from
  std::size_t line = 0;         ///< line in the file it was read from (0 when made in code)
};

}  // namespace hrad
