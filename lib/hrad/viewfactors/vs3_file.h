// NIST View3D's input format (.vs3; Walton 2002, "Calculation of obstructed view factors by
// adaptive integration", NISTIR 6925, and the View3D 3.x user manual), read and written.
//
// One record a line, its type the first word; `!` starts a comment line; blank lines are skipped:
//   T text                          title
//   C key=value ...                 control: encl (1: the surfaces form an enclosure; its rows are
//                                   then closed by the least-squares adjustment), list, eps, maxU,
//                                   maxO, minO, row, col, emit, out (View3D's own integration and
//                                   output settings: read and checked, not needed here)
//   F 3                             three-dimensional geometry (2 is refused)
//   V n x y z                       vertex n (numbered 1, 2, ... in order)
//   S n v1 v2 v3 v4 base cmb emit name
//                                   surface n (numbered in order across S, M, N, O): a triangle
//                                   (v4 = 0) or a convex quad, counter-clockwise seen from the side
//                                   that radiates; base 0; cmb > 0 combines this surface into
//                                   surface cmb (one row and column for both); emit the
//                                   emissivity in (0, 1]; name optional (no spaces)
//   M ...  mask: a subsurface of surface `base` (in its plane, inside it), a surface of its own whose
//          area is taken out of its base
//   N ...  null: a hole in surface `base`, neither surface nor obstruction
//   O ...  obstruction only: blocks, but has no row or column
//   E or End                        end of data (the rest of the file is ignored)
// A base with masks or holes becomes the convex pieces of the base minus them (each subtracted
// convex polygon H splits a piece P into P minus the half-planes of H's edges taken in turn, a
// disjoint convex partition). Any defect is an hrad::Error naming file:line.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/viewfactors/surface_units.h"

namespace hrad {

struct Vs3Model {
  std::string title;
  bool enclosure = false;  ///< encl=1 on the control line
  Scene scene;             ///< one input face per S, M and O record (several for a base with holes)
  SurfaceUnits units;      ///< one unit per S or M surface not combined into another, in file order
};

Vs3Model read_vs3(const std::string& path, std::vector<std::string>* warnings = nullptr);

/// Writes `scene` as View3D input: one S record per patch, the patches of one input face combined
/// (cmb) into its first, emissivity 1 - reflectance (mean over channels), coordinates in 17
/// significant digits (read back bit for bit). Faces named by `units` (face_units()).
void write_vs3(std::ostream& out, const Scene& scene, const SurfaceUnits& units, const std::string& title);

}  // namespace hrad
