// Emitters whose direct light stands out from the light a room already has, and the patches near
// them: where a lamp's near field (the dark side of its plane, the peak of its light on the faces
// beside it) is worth resolving (io/emitter_planes.h, `hrad solve --source-levels auto`).
#pragma once

#include <vector>

#include "hrad/core/scene.h"

namespace hrad {

/// A lamp's near field: patches within this many times its diameter of it (bounding boxes).
inline constexpr double kLampReach = 1.0;

/// B_mean = Ebar / (1 - rhobar) per channel, the closed-room radiosity of the scene's area-mean
/// emission and reflectance (rhobar at most 0.999); 0 when nothing emits.
Rgb mean_radiosity(const Scene& scene);

/// The patches whose emission exceeds mean_radiosity() (channels summed): none in a furnace, where
/// every face emits alike.
std::vector<int> bright_emitters(const Scene& scene);

/// For each patch, the bright emitters (patch indices, ascending) whose bounding box, grown on every
/// side by `reach` times the emitter's diameter, meets the patch's; an emitter is not near itself.
/// A sweep along x over both kinds of box.
std::vector<std::vector<int>> near_bright_emitters(const Scene& scene, double reach);

}  // namespace hrad
