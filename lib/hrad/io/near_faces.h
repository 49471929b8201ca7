// Faces a hair in front of other faces and facing them: a cabinet's back a millimetre from its wall,
// a box's bottom a centimetre above the floor. The face behind is dark where the near one covers it
// and lit around it: a jump along the near face's outline that elements at --aeps average away, so
// the near face gathers the element's mean (SPLASH-2's room: faces 1 unit from a wall reflect 20x
// what the Monte Carlo ruler finds; the generated office's boxes 10% too much). Cutting the face
// behind along the near face's outline puts the jump on patch boundaries (discontinuity meshing:
// Heckbert 1992; Lischinski, Tampieri & Greenberg 1992), as the bundled Cornell box's floor is cut
// around the blocks' feet by hand. read_scene() cuts by default; `hrad solve --no-cut-near-faces` keeps
// the faces whole.
#pragma once

#include <cstddef>
#include <string>

#include "hrad/core/scene.h"

namespace hrad {

/// How near: a patch is cut along the outline of a patch that faces it, parallel to it, at most this
/// many times that patch's diameter in front of it.
inline constexpr double kNearFaceGap = 0.1;

/// What find_near_faces() found and cut_near_faces() did.
struct NearCuts {
  std::size_t pairs = 0;            ///< (patch cut, patch whose outline cut it) pairs
  std::size_t splitting_pairs = 0;  ///< of them, pairs whose outline crosses the patch cut (not enclosing it)
  std::size_t patches_added = 0;    ///< patches beyond the scene's before (cut_near_faces() only)
  int first_behind = -1;            ///< the first splitting pair's faces (indices into Scene::faces), -1 when none
  int first_front = -1;
  double first_gap = 0.0;  ///< the first splitting pair's distance between the planes
};

/// The pairs cut_near_faces() would cut, without cutting: `hrad solve --no-cut-near-faces` warns of them
/// (the face behind then gathers its elements' mean across the near face's shadow), `hrad info` names them.
NearCuts find_near_faces(const Scene& scene, double gap = kNearFaceGap);

/// The warning `hrad solve` and `hrad sweep` print with --no-cut-near-faces for find_near_faces()'s splitting
/// pairs of `uncut`, naming the file, the count and the first pair's lines and gap; "" when none.
std::string near_faces_warning(const Scene& uncut);

/// The note `hrad info` prints for the same pairs of `uncut`, as find_near_faces(uncut) found them
/// (`near`): what the solvers cut (`patches_added` patches more, as read_scene() cuts them); "" when
/// none.
std::string near_faces_note(const Scene& uncut, const NearCuts& near, std::size_t patches_added);

/// Cuts every patch along the outline, projected onto its plane, of each patch of another face that
/// faces it from at most `gap` times its own diameter in front (parallel: normals opposite within
/// 1e-6). Faces keep their areas; their patch lists grow. Candidates are found by bucketing the
/// patches by their normal's direction and sweeping their planes' offsets.
NearCuts cut_near_faces(Scene& scene, double gap = kNearFaceGap);

}  // namespace hrad
