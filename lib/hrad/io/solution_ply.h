// A solved radiosity field as a PLY file (binary little endian, io/ply_file.h reads it back).
//
// Layout (every element property a PLY viewer ignores is still readable by hrad):
//   element vertex: x y z (double), red green blue (uchar: tone_map(vertex_radiosity, exposure)),
//                   radiosity_r radiosity_g radiosity_b (double: Solution::vertex_radiosity)
//   element face:   vertex_indices (CCW), radiosity_r radiosity_g radiosity_b (double:
//                   Solution::face_radiosity), patch (int: Solution::face_patch)
// Positions are doubles, so every element survives (a 1e-6 element 1 km from the origin collapsed
// to a point in 32-bit floats). Axes: scenes are +Y up (OBJ and glTF convention); Blender imports
// PLY without turning it (+Z up), so positions are stored as (x, -z, y), a header comment says so,
// and the reader turns a file with that comment back exactly (a permutation and a sign change).
// patch_radiosity is not stored: the reader recomputes it as the area-weighted mean of the faces of
// each patch, which is its definition in Solution.
#pragma once

#include <ostream>
#include <string>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"

namespace hrad {

/// Writes `solution` to `path` atomically (temporary file + rename); vertex colours use
/// tone_map(..., exposure). Throws hrad::Error naming `path` if the arrays are inconsistent or
/// the file cannot be written.
void write_solution_ply(const std::string& path, const Solution& solution, double exposure);
/// The same to a stream (binary); `path` only names the file in messages.
void write_solution_ply(std::ostream& out, const Solution& solution, double exposure, const std::string& path);

/// Reads a PLY written by write_solution_ply. A missing or unreadable file, or one without the
/// radiosity and patch properties, is an hrad::Error naming `path`.
Solution read_solution_ply(const std::string& path);

/// Throws hrad::Error naming `solution_path` when a face's patch id is not a patch of `scene`
/// (read from `scene_path`): a solution of another scene.
void check_solution_patches(const Solution& solution, const std::string& solution_path, const Scene& scene,
                            const std::string& scene_path);

}  // namespace hrad
