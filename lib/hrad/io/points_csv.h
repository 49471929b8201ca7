// Probe points from CSV: one point a row, the columns x,y,z,nx,ny,nz (a header naming exactly
// these, in any order; blank lines are skipped). The normal is the side the probe receives light
// from; it is returned as a unit vector.
//
//   x,y,z,nx,ny,nz
//   0.5,0.25,1.0,0,0,1
//
// Any defect (a missing file or header, a header with other columns, a row with too few or too
// many cells, a cell that is not a number, a non-finite number, a zero normal) is an hrad::Error
// whose one-line message names the file and line ("P.csv:4: column ny: 'abc' is not a number").
#pragma once

#include <string>
#include <vector>

#include "hrad/core/probe_point.h"

namespace hrad {

/// Reads `path`; each point's `line` is its line in the file.
std::vector<ProbePoint> read_points_csv(const std::string& path);

}  // namespace hrad
