#include "hrad/io/ply_file.h"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

#include <fmt/format.h>

#include "hrad/core/error.h"

namespace hrad {
namespace {

// Largest list length and element count accepted: far beyond any scene, small enough that a lying
// header cannot make the reader reserve absurd memory before the body proves it short.
constexpr long long kMaxCount = 2'000'000'000LL;
constexpr long long kMaxListLength = 1'000'000;

int type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

struct Layout {
  int size = 0;        ///< scalar or item size in bytes
  int count_size = 0;  ///< list count size; 0 for a scalar
  std::string count_type;
};

// A binary value of PLY type `type` at `p`, as a double (exact for every PLY type but none wider).
double decode(const std::string& type, const char* p, bool swap) {
  unsigned char b[8];
  const int n = type_size(type);
  std::memcpy(b, p, static_cast<std::size_t>(n));
  if (swap)
    for (int i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
  const auto as = [&](auto v) {
    std::memcpy(&v, b, sizeof v);
    return static_cast<double>(v);
  };
  if (type == "char" || type == "int8") return as(std::int8_t{});
  if (type == "uchar" || type == "uint8") return as(std::uint8_t{});
  if (type == "short" || type == "int16") return as(std::int16_t{});
  if (type == "ushort" || type == "uint16") return as(std::uint16_t{});
  if (type == "int" || type == "int32") return as(std::int32_t{});
  if (type == "uint" || type == "uint32") return as(std::uint32_t{});
  if (type == "float" || type == "float32") return as(float{});
  return as(double{});
}

}  // namespace

const PlyProperty* PlyElement::property(const std::string& wanted) const {
  for (const PlyProperty& p : properties)
    if (p.name == wanted) return &p;
  return nullptr;
}

const PlyElement* PlyData::element(const std::string& wanted) const {
  for (const PlyElement& e : elements)
    if (e.name == wanted) return &e;
  return nullptr;
}

bool looks_like_ply(const std::string& bytes) { return bytes.rfind("ply\n", 0) == 0 || bytes.rfind("ply\r\n", 0) == 0; }

PlyData parse_ply(const std::string& path, const std::string& bytes) {
  auto fail = [&](const std::string& what) { throw Error(fmt::format("{}: not a readable PLY file: {}", path, what)); };
  if (!looks_like_ply(bytes)) fail("it does not start with 'ply'");
  std::size_t header_end = std::string::npos;
  for (std::size_t at = bytes.find("end_header"); at != std::string::npos; at = bytes.find("end_header", at + 1))
    if (at > 0 && bytes[at - 1] == '\n') {
      header_end = at;
      break;
    }
  if (header_end == std::string::npos) fail("no end_header");
  std::size_t body = bytes.find('\n', header_end);
  if (body == std::string::npos) fail("nothing after end_header");
  ++body;

  PlyData ply;
  std::vector<std::vector<Layout>> layouts;
  std::istringstream header(bytes.substr(0, header_end));
  std::string line;
  std::size_t line_no = 0;
  while (std::getline(header, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      std::string version;
      words >> ply.format >> version;
    } else if (key == "comment" || key == "obj_info") {
      if (key == "comment") {
        ply.comments.push_back(line.size() > 8 ? line.substr(8) : "");
        ply.comment_lines.push_back(line_no);
      }
    } else if (key == "element") {
      PlyElement e;
      long long count = -1;
      if (!(words >> e.name >> count) || count < 0 || count > kMaxCount)
        fail(fmt::format("header line {}: bad element line '{}'", line_no, line));
      e.count = static_cast<std::size_t>(count);
      ply.elements.push_back(e);
      layouts.emplace_back();
    } else if (key == "property") {
      if (ply.elements.empty()) fail(fmt::format("header line {}: property before any element", line_no));
      PlyProperty prop;
      Layout layout;
      std::string type;
      words >> type;
      if (type == "list") {
        prop.list = true;
        words >> layout.count_type >> prop.type;
        layout.count_size = type_size(layout.count_type);
        layout.size = type_size(prop.type);
        if (layout.count_size == 0 || layout.size == 0 || layout.count_type == "float" || layout.count_type == "double")
          fail(fmt::format("header line {}: bad list type '{}'", line_no, line));
      } else {
        prop.type = type;
        layout.size = type_size(type);
        if (layout.size == 0) fail(fmt::format("header line {}: unknown type in '{}'", line_no, line));
      }
      if (!(words >> prop.name)) fail(fmt::format("header line {}: property without a name", line_no));
      ply.elements.back().properties.push_back(std::move(prop));
      layouts.back().push_back(layout);
    } else if (key != "ply" && !key.empty()) {
      fail(fmt::format("header line {}: unknown keyword '{}'", line_no, key.substr(0, 32)));
    }
  }
  const bool ascii = ply.format == "ascii";
  const bool big = ply.format == "binary_big_endian";
  if (!ascii && !big && ply.format != "binary_little_endian") fail(fmt::format("unknown format '{}'", ply.format));
  const bool swap = big == (std::endian::native == std::endian::little);

  if (ascii) {
    const char* p = bytes.data() + body;
    const char* const end = bytes.data() + bytes.size();
    const auto next_number = [&](const PlyElement& e, std::size_t r) {
      while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
      double x = 0.0;
      const auto [after, ec] = std::from_chars(p, end, x);
      if (p == end) fail(fmt::format("truncated in element '{}' record {}", e.name, r));
      if (ec != std::errc() || (after < end && !std::isspace(static_cast<unsigned char>(*after))))
        fail(fmt::format("element '{}' record {}: '{}' is not a number", e.name, r,
                         std::string(p, std::min<std::size_t>(16, static_cast<std::size_t>(end - p)))));
      p = after;
      return x;
    };
    for (PlyElement& e : ply.elements)
      for (std::size_t r = 0; r < e.count; ++r)
        for (PlyProperty& prop : e.properties) {
          if (!prop.list) {
            prop.values.push_back(next_number(e, r));
            continue;
          }
          if (prop.offsets.empty()) prop.offsets.push_back(0);
          const double n = next_number(e, r);
          if (!(n >= 0 && n <= kMaxListLength && n == std::floor(n)))
            fail(fmt::format("bad list length {} in element '{}' record {}", n, e.name, r));
          for (long long k = 0; k < static_cast<long long>(n); ++k) prop.values.push_back(next_number(e, r));
          prop.offsets.push_back(prop.values.size());
        }
    return ply;
  }

  std::size_t at = body;
  for (std::size_t ei = 0; ei < ply.elements.size(); ++ei) {
    PlyElement& e = ply.elements[ei];
    for (std::size_t r = 0; r < e.count; ++r)
      for (std::size_t pi = 0; pi < e.properties.size(); ++pi) {
        PlyProperty& prop = e.properties[pi];
        const Layout& layout = layouts[ei][pi];
        std::size_t n = 1;
        if (prop.list) {
          if (at + layout.count_size > bytes.size())
            fail(fmt::format("truncated in element '{}' record {}", e.name, r));
          const double count = decode(layout.count_type, bytes.data() + at, swap);
          if (!(count >= 0 && count <= kMaxListLength))
            fail(fmt::format("bad list length {} in element '{}' record {}", count, e.name, r));
          n = static_cast<std::size_t>(count);
          at += layout.count_size;
          if (prop.offsets.empty()) prop.offsets.push_back(0);
        }
        if (at + n * layout.size > bytes.size()) fail(fmt::format("truncated in element '{}' record {}", e.name, r));
        for (std::size_t k = 0; k < n; ++k, at += layout.size)
          prop.values.push_back(decode(prop.type, bytes.data() + at, swap));
        if (prop.list) prop.offsets.push_back(prop.values.size());
      }
  }
  return ply;
}

}  // namespace hrad
