// Writing a view-factor matrix for other programs. Values are F_uv = E_uv / A_u in 17 significant
// digits (a double read back is the same double), rows and columns in unit order.
//   dense      CSV, one row per unit, F from that unit to each unit, no header (.csv)
//   triplets   CSV "i,j,F" under that header, 0-based, only nonzero factors (large models)
//   mtx        Matrix Market coordinate real general, 1-based (NIST's Matrix Market exchange format)
//   view3d     View3D's text output layout (format 0): a header line, the areas on one line, one
//              line of factors per surface, the emissivities on one line (.txt)
#pragma once

#include <ostream>
#include <string>

#include "hrad/viewfactors/surface_units.h"
#include "hrad/viewfactors/view_factor_matrix.h"

namespace hrad {

enum class MatrixFormat { kDense, kTriplets, kMatrixMarket, kView3d };

/// The format for `name` ("dense", "triplets", "mtx", "view3d"), or, when `name` is empty, for the
/// extension of `path` (.csv dense, .mtx, .txt view3d); hrad::Error naming `option` otherwise.
MatrixFormat matrix_format(const std::string& name, const std::string& path, const std::string& option);

void write_matrix(std::ostream& out, const ViewFactorMatrix& m, const SurfaceUnits& units, MatrixFormat format);

}  // namespace hrad
