// PLY files (Turk 1994, "The PLY polygon file format") read as tables of numbers, in double
// precision: ascii, binary_little_endian and binary_big_endian; every scalar type; list properties.
//
// Why not OpenMesh's PLY reader and writer (used before): OpenMesh 9.0 stores vertex positions as
// 32-bit floats both ways (x = 1000.000001 reads back as 1000.0), so a 1e-6 element in a 1 km room
// collapsed to a point; no other Debian library reads PLY in double precision. The structure is
// checked before anything is read (every record the header announces must be there), so a truncated
// or lying file is a one-line error naming the file, not an endless loop or an overrun.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace hrad {

struct PlyProperty {
  std::string name;
  std::string type;  ///< item type as written ("double", "float", "uchar", ...)
  bool list = false;
  /// Scalars: one value per record. Lists: the items of record r are values[offsets[r], offsets[r + 1]).
  std::vector<double> values;
  std::vector<std::size_t> offsets;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
  /// The property called `name`, or null.
  const PlyProperty* property(const std::string& name) const;
};

struct PlyData {
  std::string format;                 ///< "ascii", "binary_little_endian" or "binary_big_endian"
  std::vector<std::string> comments;  ///< text after "comment " in the header, in order
  std::vector<std::size_t> comment_lines;  ///< the header line of each comment
  std::vector<PlyElement> elements;
  /// The element called `name`, or null.
  const PlyElement* element(const std::string& name) const;
};

/// True when `bytes` start like a PLY file ("ply" and a line end).
bool looks_like_ply(const std::string& bytes);

/// Parses the PLY in `bytes` (read from `path`, which messages name). hrad::Error on any defect:
/// "path: not a readable PLY file: truncated in element 'face' record 12".
PlyData parse_ply(const std::string& path, const std::string& bytes);

}  // namespace hrad
