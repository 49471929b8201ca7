#include "hrad/gather/photometry.h"

namespace hrad {

std::optional<EmissionUnits> parse_emission_units(std::string_view text) {
  if (text == "lm/m2" || text == "lm/m^2") return EmissionUnits::lumens_per_m2;
  if (text == "W/m2" || text == "W/m^2") return EmissionUnits::watts_per_m2;
  return std::nullopt;
}

std::string to_string(EmissionUnits units) { return units == EmissionUnits::lumens_per_m2 ? "lm/m2" : "W/m2"; }

double luminous_efficacy(EmissionUnits units) { return units == EmissionUnits::lumens_per_m2 ? 1.0 : 179.0; }

double luminance_weighted(const Rgb& v) { return 0.265074126 * v[0] + 0.670114631 * v[1] + 0.064811243 * v[2]; }

}  // namespace hrad
