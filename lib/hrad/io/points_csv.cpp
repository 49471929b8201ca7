#include "hrad/io/points_csv.h"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/io/csv_number.h"
#include "hrad/io/fccp_csv.h"

namespace hrad {
namespace {

constexpr std::array<const char*, 6> kColumns = {"x", "y", "z", "nx", "ny", "nz"};
constexpr const char* kHeader = "x,y,z,nx,ny,nz";

}  // namespace

std::vector<ProbePoint> read_points_csv(const std::string& path) {
  using Reader = io::CSVReader<6, io::trim_chars<' ', '\t'>, io::no_quote_escape<','>, io::throw_on_overflow,
                               io::empty_line_comment>;
  std::vector<ProbePoint> points;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw_at(path, 0, "is a folder, not a points CSV file");
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) throw_at(path, 0, fmt::format("cannot open: {}", std::strerror(errno)));
  std::unique_ptr<Reader> reader;
  try {
    reader = std::make_unique<Reader>(path, file);  // takes ownership of `file`
  } catch (const io::error::base&) {
    throw_at(path, 0, "cannot read");
  }
  try {
    reader->read_header(io::ignore_no_column, kColumns[0], kColumns[1], kColumns[2], kColumns[3], kColumns[4],
                        kColumns[5]);
  } catch (const io::error::header_missing&) {
    throw_at(path, 0, fmt::format("empty file: expected the header {}", kHeader));
  } catch (const io::error::missing_column_in_header& e) {
    throw_at(path, reader->get_file_line(),
             fmt::format("expected the header {}: no column '{}'", kHeader, e.column_name));
  } catch (const io::error::extra_column_in_header& e) {
    throw_at(path, reader->get_file_line(),
             fmt::format("expected the header {}: unexpected column '{}'", kHeader, e.column_name));
  } catch (const io::error::duplicated_column_in_header& e) {
    throw_at(path, reader->get_file_line(),
             fmt::format("expected the header {}: column '{}' twice", kHeader, e.column_name));
  } catch (const io::error::base&) {
    throw_at(path, reader->get_file_line(), fmt::format("expected the header {}", kHeader));
  }
  char* cells[6] = {};
  for (;;) {
    try {
      if (!reader->read_row(cells[0], cells[1], cells[2], cells[3], cells[4], cells[5])) break;
    } catch (const io::error::too_few_columns& e) {
      throw_at(path, static_cast<std::size_t>(e.file_line), fmt::format("too few cells: expected 6 ({})", kHeader));
    } catch (const io::error::too_many_columns& e) {
      throw_at(path, static_cast<std::size_t>(e.file_line), fmt::format("too many cells: expected 6 ({})", kHeader));
    } catch (const io::error::line_length_limit_exceeded& e) {
      throw_at(path, static_cast<std::size_t>(e.file_line), "line too long");
    } catch (const io::error::base&) {
      throw_at(path, reader->get_file_line(), "cannot parse the row");
    }
    const std::size_t line = reader->get_file_line();
    double v[6];
    for (int c = 0; c < 6; ++c) v[c] = parse_csv_number(path, line, kColumns[static_cast<std::size_t>(c)], cells[c]);
    ProbePoint p;
    p.position = Vec3(v[0], v[1], v[2]);
    const Vec3 normal(v[3], v[4], v[5]);
    const double length = normal.stableNorm();
    if (!(length > 0.0)) throw_at(path, line, "zero normal (nx, ny, nz)");
    p.normal = normal / length;
    if (!p.normal.allFinite()) throw_at(path, line, "normal (nx, ny, nz) too large to normalise");
    p.line = line;
    points.push_back(p);
  }
  return points;
}

}  // namespace hrad
