#include "hrad/io/face_files.h"

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hrad/core/error.h"
#include "hrad/io/csv_number.h"
#include "hrad/io/fccp_csv.h"

namespace hrad {
namespace {

constexpr std::array<const char*, 9> kColumns = {"face",           "group",          "area",
                                                 "radiosity_r",    "radiosity_g",    "radiosity_b",
                                                 "radiosity_r_se", "radiosity_g_se", "radiosity_b_se"};
constexpr const char* kHeader =
    "face,group,area,radiosity_r,radiosity_g,radiosity_b,radiosity_r_se,radiosity_g_se,radiosity_b_se";

Rgb rgb_of(const std::string& path, const nlohmann::json& j, const char* what, std::size_t face) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw_at(path, 0, fmt::format("patches[{}].{}: expected three numbers", face, what));
  return Rgb(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

}  // namespace

std::vector<FaceRecord> read_report_faces(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw_at(path, 0, "is a folder, not a solve report");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_at(path, 0, fmt::format("cannot open: {}", std::strerror(errno)));
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw_at(path, 0, fmt::format("not JSON (at byte {})", e.byte));
  }
  if (!j.is_object() || !j.contains("patches") || !j["patches"].is_array())
    throw_at(path, 0, "no 'patches' array: not a report of `hrad solve --report`");
  std::vector<FaceRecord> faces;
  const nlohmann::json& patches = j["patches"];
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const nlohmann::json& p = patches[i];
    if (!p.is_object() || !p.contains("area") || !p["area"].is_number() || !p.contains("emission") ||
        !p.contains("radiosity"))
      throw_at(path, 0, fmt::format("patches[{}]: expected area, emission and radiosity", i));
    FaceRecord f;
    try {
      f.line = p.value("line", std::size_t{0});
      f.group = p.value("group", std::string());
      f.material = p.value("material", std::string());
    } catch (const nlohmann::json::exception&) {
      throw_at(path, 0, fmt::format("patches[{}]: line, group or material of the wrong type", i));
    }
    f.area = p["area"].get<double>();
    f.emission = rgb_of(path, p["emission"], "emission", i);
    f.radiosity = rgb_of(path, p["radiosity"], "radiosity", i);
    faces.push_back(std::move(f));
  }
  return faces;
}

std::vector<FaceRecord> read_ruler_faces(const std::string& path) {
  using Reader = io::CSVReader<9, io::trim_chars<' ', '\t'>, io::double_quote_escape<',', '"'>, io::throw_on_overflow,
                               io::empty_line_comment>;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw_at(path, 0, "is a folder, not a face CSV file");
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) throw_at(path, 0, fmt::format("cannot open: {}", std::strerror(errno)));
  std::unique_ptr<Reader> reader;
  try {
    reader = std::make_unique<Reader>(path, file);  // takes ownership of `file`
    reader->read_header(io::ignore_no_column, kColumns[0], kColumns[1], kColumns[2], kColumns[3], kColumns[4],
                        kColumns[5], kColumns[6], kColumns[7], kColumns[8]);
  } catch (const io::error::header_missing&) {
    throw_at(path, 0, fmt::format("empty file: expected the header {}", kHeader));
  } catch (const io::error::base&) {
    throw_at(path, reader ? reader->get_file_line() : 0,
             fmt::format("expected the header {} (hrad reference --faces)", kHeader));
  }
  std::vector<FaceRecord> faces;
  char* cells[9] = {};
  for (;;) {
    try {
      if (!reader->read_row(cells[0], cells[1], cells[2], cells[3], cells[4], cells[5], cells[6], cells[7], cells[8]))
        break;
    } catch (const io::error::too_few_columns& e) {
      throw_at(path, static_cast<std::size_t>(e.file_line), "too few cells: expected 9");
    } catch (const io::error::too_many_columns& e) {
      throw_at(path, static_cast<std::size_t>(e.file_line), "too many cells: expected 9");
    } catch (const io::error::base&) {
      throw_at(path, reader->get_file_line(), "cannot parse the row");
    }
    const std::size_t line = reader->get_file_line();
    double v[9] = {};
    for (int c = 0; c < 9; ++c)
      if (c != 1) v[c] = parse_csv_number(path, line, kColumns[static_cast<std::size_t>(c)], cells[c]);
    if (v[0] != static_cast<double>(faces.size()))
      throw_at(path, line,
               fmt::format("column face: expected face {} (rows in file order), got '{}'", faces.size(), cells[0]));
    FaceRecord f;
    f.line = line;
    f.group = cells[1];
    f.area = v[2];
    f.radiosity = Rgb(v[3], v[4], v[5]);
    f.radiosity_se = Rgb(v[6], v[7], v[8]);
    faces.push_back(std::move(f));
  }
  if (faces.empty()) throw_at(path, 0, "no rows: no faces");
  return faces;
}

}  // namespace hrad
