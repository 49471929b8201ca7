// Reading scenes from Wavefront OBJ + MTL.
//
// Scene format (README "Scene format"):
//   * each `f` is one input polygon; its front is the side its counter-clockwise vertex order
//     faces (right-hand rule); the `o`/`g` name before it is its group;
//   * `usemtl NAME` picks a material of the `mtllib`: `Kd r g b` is the diffuse reflectance
//     (each channel in [0, 1)), `Ke r g b` the emitted exitance (>= 0);
//   * convex triangles and quads become one patch each; other faces are triangulated; a face
//     whose vertices leave its plane by more than `planarity_tolerance` times its diameter is
//     split into triangles with a warning; zero-area faces are skipped with a warning.
// Any other defect is an hrad::Error whose message names the file and line.
#pragma once

#include <string>
#include <vector>

#include "hrad/core/scene.h"

namespace hrad {

struct ObjReadOptions {
  double planarity_tolerance = 1e-7;  ///< relative to the face's diameter
  double max_abs_coordinate = 1e12;   ///< larger coordinates are rejected as garbage
};

/// Reads `path` (and the MTL files it names, relative to its folder). Warnings, one line each
/// and naming file and line, are appended to `warnings` when it is not null.
Scene read_obj_scene(const std::string& path, std::vector<std::string>* warnings = nullptr,
                     const ObjReadOptions& options = {});

}  // namespace hrad
