#include "hrad/io/scene_directives.h"

#include <sstream>

#include <fmt/format.h>

#include "hrad/core/error.h"

namespace hrad::detail {

void declare_emission_units(Scene& scene, std::string_view value, const std::string& where) {
  const std::optional<EmissionUnits> units = parse_emission_units(value);
  if (!units) throw Error(fmt::format("{}: emission-units '{}' is not lm/m2 or W/m2", where, value));
  if (scene.emission_units && scene.emission_units->units != *units)
    throw Error(fmt::format("{}: emission-units {} contradicts {} declared at {}", where, to_string(*units),
                            to_string(scene.emission_units->units), scene.emission_units->where));
  if (!scene.emission_units) scene.emission_units = DeclaredEmissionUnits{*units, where};
}

void apply_scene_comment(Scene& scene, const std::string& file, std::size_t line, std::string_view comment) {
  const std::size_t first = comment.find_first_not_of(" \t");
  if (first == std::string_view::npos || comment.substr(first, 5) != "@hrad") return;
  if (comment.size() > first + 5 && comment[first + 5] != ' ' && comment[first + 5] != '\t') return;
  std::istringstream words{std::string(comment.substr(first + 5))};
  std::string key, value, extra;
  words >> key >> value >> extra;
  const std::string where = fmt::format("{}:{}", file, line);
  if (key != "emission-units")
    throw Error(fmt::format("{}: unknown hrad declaration '{}' (known: emission-units)", where, key));
  if (value.empty() || !extra.empty())
    throw Error(fmt::format("{}: '@hrad emission-units' takes one unit, lm/m2 or W/m2", where));
  declare_emission_units(scene, value, where);
}

}  // namespace hrad::detail
