// The JSON report of a view-factor matrix: per surface its area, emissivity, row sum, the sky's
// share (1 - row sum: what an open model's surface sends out of it), the standard error of the row
// sum from sampled visibility and the bound of what skipped pairs could hold; and over the matrix
// the largest reciprocity error, the largest closure error and the work done.
#pragma once

#include <nlohmann/json.hpp>

#include "hrad/viewfactors/closure.h"
#include "hrad/viewfactors/surface_units.h"
#include "hrad/viewfactors/view_factor_matrix.h"

namespace hrad {

/// `closure` may be null (no adjustment was asked for).
nlohmann::json view_factor_report(const ViewFactorMatrix& m, const SurfaceUnits& units,
                                  const ViewFactorOptions& options, const ClosureReport* closure);

}  // namespace hrad
