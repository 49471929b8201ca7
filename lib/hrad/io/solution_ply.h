// A solved radiosity field as a PLY file (OpenMesh's PLY reader and writer, binary little endian).
//
// Layout (every element property a PLY viewer ignores is still readable by hrad):
//   element vertex: x y z (float), red green blue (uchar: tone_map(vertex_radiosity, exposure)),
//                   radiosity_r radiosity_g radiosity_b (double: Solution::vertex_radiosity)
//   element face:   vertex_indices (CCW), radiosity_r radiosity_g radiosity_b (double:
//                   Solution::face_radiosity), patch (int: Solution::face_patch)
// Positions are 32-bit floats (OpenMesh's PLY writer stores points as float); radiosities are
// exact. patch_radiosity is not stored: the reader recomputes it as the area-weighted mean of the
// faces of each patch, which is its definition in Solution.
// A face that OpenMesh's half-edge mesh cannot take (a non-manifold edge or vertex) is written
// with its own copies of its vertices, so such a mesh reads back with more vertices.
#pragma once

#include <string>

#include "hrad/core/solution.h"

namespace hrad {

/// Writes `solution` to `path` atomically (temporary file + rename); vertex colours use
/// tone_map(..., exposure). Throws hrad::Error naming `path` if the arrays are inconsistent or
/// the file cannot be written.
void write_solution_ply(const std::string& path, const Solution& solution, double exposure);

/// Reads a PLY written by write_solution_ply. A missing or unreadable file, or one without the
/// radiosity and patch properties, is an hrad::Error naming `path`.
Solution read_solution_ply(const std::string& path);

}  // namespace hrad
