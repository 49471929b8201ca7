// Form factors of the pairs of a JSON document (`hrad formfactor --json FILE`).
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
// digits; F_to_from is null for a point. Polygon pairs use hrad::polygon_to_polygon (closed form,
// both directions from one evaluation), points hrad::point_to_polygon.
// Errors (unreadable file, malformed JSON with its byte offset, a polygon with fewer than 3 vertices,
// non-finite coordinates, zero area, or vertices off its plane by more than 1e-7 of its diameter)
// are one line naming the file and the pair, with a non-zero exit.
#pragma once

#include <string>

namespace hrad {

/// Evaluates every pair of the JSON document `text` (read from `path`, used in messages) and returns
/// the output document. Throws hrad::Error, one line naming `path` and the pair, on any defect.
std::string evaluate_formfactor_json(const std::string& text, const std::string& path);

}  // namespace hrad
