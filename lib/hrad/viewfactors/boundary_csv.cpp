#include "hrad/viewfactors/boundary_csv.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "hrad/core/error.h"

namespace hrad {
namespace {

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

}  // namespace

std::vector<SurfaceCondition> read_boundary_csv(const std::string& path, int surfaces) {
  std::ifstream in(path);
  if (!in) throw_at(path, 0, "cannot open");
  std::vector<SurfaceCondition> out(static_cast<std::size_t>(surfaces));
  std::vector<std::size_t> seen(static_cast<std::size_t>(surfaces), 0);
  std::size_t line = 0;
  bool header = false;
  for (std::string text; std::getline(in, text);) {
    ++line;
    if (trim(text).empty()) continue;
    std::vector<std::string> cells;
    std::istringstream row(text);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(trim(cell));
    if (!text.empty() && trim(text).back() == ',') cells.emplace_back();
    if (!header) {
      if (cells != std::vector<std::string>{"surface", "temperature", "heat_flux"})
        throw_at(path, line, "the header must be surface,temperature,heat_flux");
      header = true;
      continue;
    }
    if (cells.size() != 3) throw_at(path, line, fmt::format("{} cells (expected 3)", cells.size()));
    int s = -1;
    const auto [end, ec] = std::from_chars(cells[0].data(), cells[0].data() + cells[0].size(), s);
    if (ec != std::errc() || end != cells[0].data() + cells[0].size() || s < 0 || s >= surfaces)
      throw_at(path, line, fmt::format("surface '{}' is not a surface number in [0, {})", cells[0], surfaces));
    if (seen[static_cast<std::size_t>(s)] != 0)
      throw_at(path, line, fmt::format("surface {} was given on line {}", s, seen[static_cast<std::size_t>(s)]));
    seen[static_cast<std::size_t>(s)] = line;
    if (cells[1].empty() == cells[2].empty()) throw_at(path, line, "give exactly one of temperature and heat_flux");
    const bool t = !cells[1].empty();
    const std::string& v = t ? cells[1] : cells[2];
    double value = 0.0;
    const auto [e2, ec2] = std::from_chars(v.data(), v.data() + v.size(), value);
    if (ec2 != std::errc() || e2 != v.data() + v.size() || !std::isfinite(value))
      throw_at(path, line, fmt::format("{} '{}' is not a finite number", t ? "temperature" : "heat_flux", v));
    if (t && value < 0.0) throw_at(path, line, fmt::format("temperature {} K is negative", value));
    out[static_cast<std::size_t>(s)] = {t ? SurfaceCondition::Kind::kTemperature : SurfaceCondition::Kind::kHeatFlux,
                                        value};
  }
  if (!header) throw_at(path, 0, "empty: no header surface,temperature,heat_flux");
  for (int s = 0; s < surfaces; ++s)
    if (seen[static_cast<std::size_t>(s)] == 0) throw_at(path, 0, fmt::format("no condition for surface {}", s));
  return out;
}

}  // namespace hrad
