// The rows and columns of a view-factor matrix: input faces (file order), groups of faces, or the
// surfaces of a View3D model (several input faces combined into one). A unit's factor is the
// area-weighted mean over its patches: A_u F_uv = sum over patches p of u and q of v of A_p F_pq.
#pragma once

#include <string>
#include <vector>

#include "hrad/core/scene.h"

namespace hrad {

struct SurfaceUnits {
  /// The unit of each input face, or -1 for a face that only obstructs (no row, no column).
  std::vector<int> of_face;
  std::vector<std::string> names;
  std::vector<double> area;        ///< sum of the areas of the unit's patches
  std::vector<double> emissivity;  ///< gray hemispherical emissivity, eps = 1 - rho (mean over channels)

  int size() const { return static_cast<int>(names.size()); }
  /// The unit of patch `p` of `scene` (-1: obstruction only).
  int of_patch(const Scene& scene, int p) const {
    return of_face[static_cast<std::size_t>(scene.patches[static_cast<std::size_t>(p)].face)];
  }
};

/// One unit per input face, in file order; named by the face's group and number ("wall#3").
SurfaceUnits face_units(const Scene& scene);
/// One unit per group (`o`/`g` name), in order of first appearance.
SurfaceUnits group_units(const Scene& scene);
/// Units from an explicit face -> unit map (View3D's combined surfaces); sets areas and emissivities
/// (the area-weighted mean of the faces' 1 - rho unless `emissivity` is given per unit).
SurfaceUnits units_from_map(const Scene& scene, std::vector<int> of_face, std::vector<std::string> names,
                            std::vector<double> emissivity = {});

}  // namespace hrad
