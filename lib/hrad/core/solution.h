// A solved radiosity field: the leaf elements as one polygon mesh with constant radiosity per
// element, plus per-vertex radiosity for smooth display. Solvers write it; io, render and
// analysis read it. Plain arrays: no OpenMesh or CGAL types cross this boundary.
#pragma once

#include <utility>
#include <vector>

#include "hrad/core/types.h"

namespace hrad {

struct Solution {
  std::vector<Vec3> vertices;            ///< leaf-mesh vertex positions
  std::vector<Rgb> vertex_radiosity;     ///< per vertex, for display (anchored at T-vertices, no cracks)
  std::vector<std::vector<int>> faces;   ///< leaf elements, counter-clockwise vertex ids (T-vertices included)
  std::vector<int> face_patch;           ///< the patch (index into Scene::patches) each leaf lies on
  std::vector<Rgb> face_radiosity;       ///< constant radiosity of each leaf element (the unknowns)
  std::vector<Rgb> patch_radiosity;      ///< area-weighted mean radiosity of each patch
  /// Optional, for figures: each link of a hierarchical solve as the segment between the centroids
  /// of its receiver and source elements (empty unless SolveOptions::record_links).
  std::vector<std::pair<Vec3, Vec3>> link_segments;
};

}  // namespace hrad
