// Declarations for hrad that a scene file carries where other readers ignore them, so the file stays
// valid for every other program: a comment line "#@hrad emission-units lm/m2" in an OBJ or MTL file
// (as Radiance's mkillum reads "#@mkillum" comment lines; Ward 1994), a header line
// "comment @hrad emission-units lm/m2" in a PLY file, and in a glTF file
// {"hrad": {"emission-units": "lm/m2"}} among the asset's extras (glTF 2.0, section 3.12: "extras",
// application-specific data). The one declaration today is the unit of the emission (Ke, emission_r/g/b,
// emissiveFactor): lm/m2 (luminous exitance) or W/m2 (radiant exitance of white light), which photometric
// output needs (`hrad probe`: illuminance in lux).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "hrad/core/scene.h"

namespace hrad::detail {

/// If `comment` (the text after the comment marker) starts with "@hrad", applies its declaration to
/// the scene; any other comment is ignored. Throws hrad::Error "file:line: ..." for an unknown
/// declaration, a bad value, or a unit that contradicts one declared before.
void apply_scene_comment(Scene& scene, const std::string& file, std::size_t line, std::string_view comment);

/// Declares the scene's emission unit from `value`, found at `where` (for messages).
void declare_emission_units(Scene& scene, std::string_view value, const std::string& where);

}  // namespace hrad::detail
