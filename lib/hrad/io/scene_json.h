// JSON summary of a scene (`hrad info --json`).
#pragma once

#include <nlohmann/json.hpp>

#include "hrad/core/scene.h"

namespace hrad {

/// {"file", "patches": count, "faces": [...], "emitters": [...], "area", "materials": {...},
///  "bounds": {"min", "max"}}: areas in the scene's unit squared.
nlohmann::json scene_summary_json(const Scene& scene);

}  // namespace hrad
