// Cells of the CSV files the commands write.
#pragma once

#include <string>

#include <fmt/format.h>

#include "hrad/core/types.h"

namespace hrad::cli {

/// A CSV cell: quoted when it holds a comma, a quote or a line break (RFC 4180).
inline std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

/// Three cells r,g,b (shortest round-trip form).
inline std::string rgb_cells(const Rgb& c) { return fmt::format("{},{},{}", c[0], c[1], c[2]); }

}  // namespace hrad::cli
