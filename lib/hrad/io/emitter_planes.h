// Faces that cross the plane of a nearby emitter: a lamp housing's reflector, a wall beside a lamp
// mounted across it. An emitter lights only the side of its plane it faces, so a face crossing that
// plane is dark on one side of the line where they meet and lit on the other, brightest right beside
// the line when the emitter is near (a derivative discontinuity of the direct light; Heckbert 1992,
// "discontinuity meshing"). Elements at --aeps average the two sides, and what gathers from them
// (the housing's other faces, the emitter itself) gets the mean of a field that is nothing like it.
// Cutting the face along the line puts the jump in slope on a patch boundary.
#pragma once

#include <cstddef>

#include "hrad/core/bright_emitters.h"
#include "hrad/core/scene.h"

namespace hrad {

/// How near: a face is cut along an emitter's plane when its bounding box meets the emitter's grown
/// on every side by this many times the emitter's diameter (the lamp's near field).
inline constexpr double kEmitterPlaneReach = kLampReach;

/// A cut is made only when each side keeps at least this fraction of the piece it splits: a sliver
/// along a wall that passes a lamp's plane a hair above it gathers and sends next to nothing.
inline constexpr double kEmitterPlaneSliver = 0.02;

/// What cut_emitter_planes() did.
struct EmitterPlaneCuts {
  std::size_t pairs = 0;          ///< (patch, emitter patch whose plane cut it) pairs
  std::size_t patches_added = 0;  ///< patches beyond the scene's before
};

/// Cuts every patch along the plane of each emitting patch it crosses within `reach` times that
/// emitter's diameter (bounding boxes), for emitters brighter than the mean radiosity of a closed
/// room of the scene's mean emission and reflectance (in a furnace, where all emit alike, none). A
/// convex piece of five corners becomes a fan of triangles. Faces keep their areas; their patch
/// lists grow.
EmitterPlaneCuts cut_emitter_planes(Scene& scene, double reach = kEmitterPlaneReach);

}  // namespace hrad
