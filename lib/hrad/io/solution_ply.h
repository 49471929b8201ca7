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
//
// A hierarchical solve's file also carries what a final gather through its links needs
// (gather/stored_links.h), as three more elements a PLY viewer skips:
//   element node:    first_child (int: the first of the element's 4 children, -1 for a leaf), one
//                    per element of the hierarchy by id (ids below the patch count are the patches'
//                    roots): the splits in the order they were made, so the hierarchy is rebuilt
//                    from the scene by the same split rule (4 bytes a node);
//   element cluster: parent (int: the parent cluster, -1 for the root), one per cluster of the
//                    volume hierarchy above the patches; none when the solve did not cluster
//                    (4 bytes a cluster);
//   element link:    p q (int: the ends, an element id >= 0 or a cluster -2 - index), partial
//                    (uchar: 1 when the refinement found the pair partly visible), hidden_p hidden_q
//                    (list int int: the patches of a cluster end that see nothing of the other end):
//                    17 bytes a link plus 4 per listed patch.
// The leaves' radiosities are the faces' (faces are the leaves in depth-first order, patch by patch);
// an interior element's is the area mean of its leaves.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"

namespace hrad {

/// The hierarchy and links of a hierarchical solve as stored (see above).
struct SolutionLinks {
  std::vector<std::int32_t> first_child;     ///< per element node
  std::vector<std::int32_t> cluster_parent;  ///< per cluster; empty without clusters
  struct Link {
    std::int32_t p = -1, q = -1;
    bool partial = false;
    std::vector<std::int32_t> hidden_p, hidden_q;  ///< patch ids, ascending
    bool operator==(const Link&) const = default;
  };
  std::vector<Link> links;
  bool operator==(const SolutionLinks&) const = default;
};

/// Writes `solution` to `path` atomically (temporary file + rename); vertex colours use
/// tone_map(..., exposure). Throws hrad::Error naming `path` if the arrays are inconsistent or
/// the file cannot be written.
/// With `links`, they are written too.
void write_solution_ply(const std::string& path, const Solution& solution, double exposure,
                        const SolutionLinks* links = nullptr);
/// The same to a stream (binary); `path` only names the file in messages.
void write_solution_ply(std::ostream& out, const Solution& solution, double exposure, const std::string& path,
                        const SolutionLinks* links = nullptr);

/// Reads a PLY written by write_solution_ply. A missing or unreadable file, or one without the
/// radiosity and patch properties, is an hrad::Error naming `path`. `links`, when given, receives
/// the stored links (nullopt when the file has no 'link' element); a link element without its node
/// element, or a value out of range (an end that is neither a stored element nor a stored cluster,
/// a flag other than 0 or 1, a split that cannot have been made), is an hrad::Error naming `path`,
/// the element and the record.
Solution read_solution_ply(const std::string& path, std::optional<SolutionLinks>* links = nullptr);

/// Throws hrad::Error naming `solution_path` when a face's patch id is not a patch of `scene` (read from
/// `scene_path`) or the face does not lie on that patch: a solution of another scene, or of this one read
/// otherwise (cut along near faces or not).
void check_solution_patches(const Solution& solution, const std::string& solution_path, const Scene& scene,
                            const std::string& scene_path);

}  // namespace hrad
