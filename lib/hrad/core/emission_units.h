// The unit a scene's emission (and so its radiosity and irradiance) is in, when the scene declares
// it: luminous exitance (lm/m^2) or radiant exitance of white light (W/m^2). hrad's solvers are
// unit-free; the unit matters only for photometric output (gather/photometry.h).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace hrad {

enum class EmissionUnits { lumens_per_m2, watts_per_m2 };

/// "lm/m2" or "W/m2" (also "lm/m^2", "W/m^2"); nullopt for anything else.
inline std::optional<EmissionUnits> parse_emission_units(std::string_view text) {
  if (text == "lm/m2" || text == "lm/m^2") return EmissionUnits::lumens_per_m2;
  if (text == "W/m2" || text == "W/m^2") return EmissionUnits::watts_per_m2;
  return std::nullopt;
}

inline std::string to_string(EmissionUnits units) {
  return units == EmissionUnits::lumens_per_m2 ? "lm/m2" : "W/m2";
}

/// A unit as a scene declared it, with where ("file:line", or a glTF JSON pointer) for messages.
struct DeclaredEmissionUnits {
  EmissionUnits units = EmissionUnits::lumens_per_m2;
  std::string where;
};

}  // namespace hrad
