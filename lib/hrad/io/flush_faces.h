// Faces lying flush on other faces: a picture modelled on its wall, a rug on its floor, a label on a
// box. The two lie in one plane, face the same way and overlap, and exact visibility cannot tell which
// is on top: light reaching the overlap would land on both, and a closed scene would absorb more than
// it emits (SPLASH-2's room: 6% of its power, from a picture covering 1.8% of its area). Every reader
// settles it as a modeller would: the face of the smaller object (its `o`/`g` group, by total area)
// lies on top; within one object the smaller face, then the later one in the file. The part of the face
// beneath that the one on top covers is cut out of it, so that the face beneath keeps only what shows.
#pragma once

#include <cstddef>

#include "hrad/core/scene.h"

namespace hrad {

/// What cut_flush_faces() did.
struct FlushCuts {
  std::size_t pairs = 0;      ///< (face on top, face beneath) pairs of overlapping patches
  double covered_area = 0.0;  ///< area cut out of the faces beneath
  int first_top = -1;         ///< the first pair's faces (indices into Scene::faces), -1 when none
  int first_beneath = -1;
  std::size_t hidden_faces = 0;  ///< faces covered entirely (left without patches)
};

/// Cuts, out of every patch, the parts that patches of other faces lying flush on top of it cover
/// (the rule above). A cut patch is replaced by convex pieces of what remains (triangles and convex
/// quadrilaterals, in its plane); faces' patch lists and areas follow. Pieces thinner than a
/// millionth of the scene's size are dropped.
FlushCuts cut_flush_faces(Scene& scene);

}  // namespace hrad
