// Per-input-face values from the files hrad writes, for scoring one answer against another
// (`hrad compare`, lib/hrad/analysis/face_error.h):
//   * a solve report (`hrad solve --report R.json`): its `patches` array, one entry per input face
//     in file order with face, line, group, material, area, emission and radiosity (RGB);
//   * the ruler's face CSV (`hrad reference --faces --out R.csv`): the columns face, group, area,
//     radiosity_r, _g, _b and radiosity_r_se, _g_se, _b_se, one row per input face in file order
//     (a group holding a comma or a quote is quoted, RFC 4180).
// Any defect (a missing file, JSON that is not a report, a CSV with other columns, a row out of
// order, a cell that is not a number) is an hrad::Error whose one-line message names the file and,
// for a CSV, the line.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "hrad/core/types.h"

namespace hrad {

struct FaceRecord {
  std::size_t line = 0;         ///< the face's line in the scene file (reports) or its row's line (CSV)
  std::string group, material;  ///< material: empty for the CSV, which does not name it
  double area = 0.0;
  std::optional<Rgb> emission;  ///< known for reports only
  Rgb radiosity = Rgb::Zero();
  Rgb radiosity_se = Rgb::Zero();  ///< the CSV's standard errors; 0 for a report
};

/// The faces of a solve report (JSON).
std::vector<FaceRecord> read_report_faces(const std::string& path);

/// The faces of a ruler's face CSV.
std::vector<FaceRecord> read_ruler_faces(const std::string& path);

}  // namespace hrad
