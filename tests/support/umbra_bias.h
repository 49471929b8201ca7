// Brightness of umbras: the leaves of a solution that see none of the light (no point across the
// leaf gathers any emission, decided by the final gather's own visibility) are lit only by
// interreflection, through links that may be coarse. Each such leaf's radiosity is compared with the
// final gather of the same solution at points across the leaf (gather/leaf_gather.h, leaf by leaf,
// exact point factors, visibility from each point), area-weighted per surface group (the OBJ's
// `o`/`g` names):
//   bias(group) = sum_L A_L (B_L - Bg_L) / sum_L A_L Bg_L,   Bg_L the leaf's mean gathered radiosity,
// summed over the three channels.
#pragma once

#include <map>
#include <string>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"

namespace hrad::test {

struct UmbraBias {
  double bias = 0.0;   ///< relative, area-weighted over the group's umbra leaves (see above)
  double worst = 0.0;  ///< the largest single leaf's (B_L - Bg_L) / Bg_L
  int leaves = 0;
};

/// Per surface group with umbra leaves; emitters excluded.
std::map<std::string, UmbraBias> umbra_bias(const Scene& scene, const Solution& solution);

}  // namespace hrad::test
