// The form-factor query document of `hrad formfactor --json FILE`: reading its pairs and writing the
// answers. The factors themselves are the formfactor module's (the command calls it); this file only
// parses and writes.
//
// FILE:
//   {"pairs": [
//     {"name": "a", "from": [[x,y,z], ...], "to": [[x,y,z], ...]},
//     {"name": "p", "from_point": [x,y,z], "from_normal": [nx,ny,nz], "to": [[x,y,z], ...]}]}
//
// | key           | meaning                                                                    |
// | ------------- | -------------------------------------------------------------------------- |
// | name          | optional label echoed in the output (default: the pair's index)            |
// | from, to      | planar polygons, >= 3 vertices, counter-clockwise seen from their front    |
// | from_point    | a differential area at this point instead of `from` ...                    |
// | from_normal   | ... facing this way (any non-zero length)                                  |
//
// Output: {"pairs": [{"name": "a", "F_from_to": ..., "F_to_from": ...}, ...]} with 17 significant
// digits; F_to_from is null for a point.
// Errors (malformed JSON with its byte offset, a polygon with fewer than 3 vertices, non-finite
// coordinates, zero area, or vertices off its plane by more than 1e-7 of its diameter) are one line
// naming the file and the pair.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hrad/core/types.h"

namespace hrad {

/// One pair of the document: from a polygon or from a differential area, to a polygon.
struct FormFactorQuery {
  std::optional<std::string> name;  ///< the pair's "name"; the output uses its index without one
  std::vector<Vec3> from;           ///< empty when the pair starts at a point
  Vec3 from_point = Vec3::Zero();   ///< with from_normal, the differential area (when `from` is empty)
  Vec3 from_normal = Vec3::Zero();  ///< unit length
  std::vector<Vec3> to;

  bool from_is_point() const { return from.empty(); }
};

/// The factors of one query; F_to_from is absent when it starts at a point (written as null).
struct FormFactorAnswer {
  double from_to = 0.0;
  std::optional<double> to_from;
};

/// The pairs of the JSON document `text` (read from `path`, used in messages), every polygon
/// checked as above. Throws hrad::Error, one line naming `path` and the pair, on any defect.
std::vector<FormFactorQuery> read_formfactor_json(const std::string& text, const std::string& path);

/// The output document for `answers[i]` of `queries[i]` (same length), ending in a newline.
std::string write_formfactor_json(std::span<const FormFactorQuery> queries, std::span<const FormFactorAnswer> answers);

}  // namespace hrad
