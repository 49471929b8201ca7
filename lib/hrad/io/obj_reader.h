// Reading scenes from Wavefront OBJ + MTL.
//
// Scene format (README "Scene format"):
//   * each `f` is one input polygon; its front is the side its counter-clockwise vertex order
//     faces (right-hand rule); the `o`/`g` name before it is its group;
//   * `usemtl NAME` picks a material of the `mtllib` (one or several files; names may hold spaces or
//     be quoted): `Kd r g b` is the diffuse reflectance (each channel in [0, 1); one value means all
//     three), `Ke r g b` the emitted exitance (>= 0); other MTL statements (Ks, Ns, Ni, d, illum,
//     the PBR extension's Pr, Pm, Ps, Pc, Pcr, aniso, map_*) are read and ignored; a face without a
//     material gets kDefaultMaterialName (reflectance kDefaultReflectance) with a warning;
//   * a UTF-8 byte order mark and comments after a statement are ignored; numbers are decimal (a
//     hex float is an error naming its line);
//   * convex triangles and quads become one patch each; other faces are triangulated; a face
//     whose vertices leave its plane by more than `planarity_tolerance` times its diameter is
//     split into triangles with a warning; zero-area faces are skipped with a warning.
// Repeated warnings of one kind are one line ("N faces ..., the first here"). Any other defect is an
// hrad::Error whose message names the file and line.
#pragma once

#include <string>
#include <vector>

#include "hrad/core/progress.h"
#include "hrad/core/scene.h"

namespace hrad {

/// Faces without a material get this one, with a warning.
inline constexpr const char* kDefaultMaterialName = "default";
inline constexpr double kDefaultReflectance = 0.5;

struct ObjReadOptions {
  /// Relative to the face's diameter; the tolerance is never below what the file's printed digits
  /// allow: sqrt(3) times 10^-d when every coordinate is printed with the same d >= 3 decimals
  /// (Blender writes 6, so a 1 m face off its plane by 1.4e-7 of its diameter is planar). 1e-5: single-precision
  /// exporters round at ~6e-8 of the coordinates' size, which is ~1e-5 of a face 200x smaller than the scene's extent;
  /// a bend that size changes no form factor beyond its own order, and truly bent faces (the
  /// published Cornell box's red wall: 1.5e-3) are still split.
  double planarity_tolerance = 1e-5;
  double max_abs_coordinate = 1e12;  ///< larger coordinates are rejected as garbage
  /// read_scene(): cut faces along the outlines of faces a hair in front of them (io/near_faces.h); a scene
  /// without such pairs is unchanged.
  bool cut_near_faces = true;
  /// read_scene(): cut faces along the planes of emitters they cross nearby (io/emitter_planes.h).
  bool cut_emitter_planes = true;
  /// Progress lines while reading large files (at most one every 2 s; none for small files).
  ProgressSink progress;
};

/// Reads `path` (and the MTL files it names, relative to its folder). Warnings, one line each
/// and naming file and line, are appended to `warnings` when it is not null.
Scene read_obj_scene(const std::string& path, std::vector<std::string>* warnings = nullptr,
                     const ObjReadOptions& options = {});

}  // namespace hrad
