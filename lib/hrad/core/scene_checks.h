// Warnings a user can act on, about scenes that read fine but would solve to a wrong-looking answer
// without a word: `hrad info` and `hrad solve` print them on stderr and the solve report lists them.
//
//   * no emitter: nothing emits (no material with Ke > 0), so every radiosity is 0;
//   * emitters exported without emission: a material whose name says it is a light ("light", "lamp",
//     "emission", "emissive", "emit", "glow") with Ke 0: Blender's OBJ exporter writes its Emission
//     shader and its lamps that way;
//   * faces facing away from the rest: a face with no point of any other face strictly in front of
//     its plane can neither receive nor send light; when such faces hold most of the area, the
//     normals point out of the room (the most common modelling mistake), so flip them;
//   * no light reaching any surface: no emitter has a face in front of it that also has the emitter
//     in front of it (every emitter faces away from everything);
//   * coplanar overlaps: patches of different faces in one plane, facing the same way, that overlap
//     (a picture or a rug flush with its wall or floor): light reaching the overlap is received by
//     both, so the solution absorbs more than the scene emits (exact visibility cannot say which
//     is on top). Found by bucketing patches by their plane and a separating-axis test per pair.
//     The scene readers cut them (io/flush_faces.h); a scene built otherwise may still have them.
// The tests are exact for flat faces (a point in front of a plane, with a tolerance of 1e-9 of the
// scene's size for points on the plane) and cost O(faces^2) at worst, stopping at the first face in front.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "hrad/core/scene.h"

namespace hrad {

/// Whether two convex patches in one plane (unit normal `n`) overlap by more than `tol` across every
/// separating direction: by the separating axis theorem two convex polygons are disjoint exactly
/// when some edge's in-plane normal separates them, so overlap means no edge separates them by
/// more than -tol (touching along an edge or at a corner is not overlap).
bool patches_overlap(const Patch& a, const Patch& b, const Vec3& n, double tol);

/// Pairs (i, j), i < j, of patches of different faces that lie in one plane (normal and offset
/// rounded to 1e-6 and 1e-7 of the scene's size), face the same way and overlap by more than 1e-7
/// of the scene's size: faces lying flush on each other. Sorted.
std::vector<std::pair<int, int>> flush_pairs(const Scene& scene);

/// Per patch, 1 when no vertex of another patch lies in front of its plane by more than 1e-9 of
/// the scene's size (its normal probably points out of the room), else 0. About linear in the
/// patches: the vertices extreme along 26 directions, then the scene's box, settle most patches.
std::vector<char> patches_facing_nothing(const Scene& scene);

/// One line per finding, without a "warning:" prefix; empty for a sound scene.
std::vector<std::string> scene_warnings(const Scene& scene);

}  // namespace hrad
