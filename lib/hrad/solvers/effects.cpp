#include "hrad/solvers/effects.h"

#include <cassert>

#include "hrad/visibility/visibility.h"

namespace hrad {

bool scene_is_gray(const Scene& scene) {
  for (const Material& m : scene.materials) {
    if (m.reflectance[0] != m.reflectance[1] || m.reflectance[0] != m.reflectance[2]) return false;
    if (m.emission[0] != m.emission[1] || m.emission[0] != m.emission[2]) return false;
  }
  return true;
}

bool scene_has_no_reflection(const Scene& scene) {
  for (const Material& m : scene.materials)
    if ((m.reflectance != 0.0).any()) return false;
  return true;
}

Effects analyse_effects(const Scene& scene, EffectsMode mode, const Visibility* visibility, bool irradiance) {
  Effects e;
  if (mode == EffectsMode::kAll) {
    e.visibility = true;
    e.color_channels = 3;
    e.bounces = true;
    e.cull_facing_away = false;
    e.reasons.push_back("all effects forced on (--effects all): visibility, 3 channels, bounces, no culling");
    return e;
  }
  if (scene_is_gray(scene)) {
    e.color_channels = 1;
    e.reasons.push_back("color: 1 channel: every reflectance and emission is gray (r == g == b)");
  } else {
    e.color_channels = 3;
    e.reasons.push_back("color: 3 channels: some reflectance or emission is coloured");
  }
  if (scene_has_no_reflection(scene) && !irradiance) {
    e.bounces = false;
    e.visibility = false;
    e.reasons.push_back("bounces: off: every reflectance is 0, so B = E and no form factor is needed");
    e.reasons.push_back("visibility: off: no form factor is needed");
  } else {
    e.bounces = true;
    e.reasons.push_back(irradiance ? "bounces: on: the gathered irradiance is asked for"
                                   : "bounces: on: some reflectance is > 0");
    assert(visibility != nullptr);
    if (visibility->scene_has_occlusion()) {
      e.visibility = true;
      e.reasons.push_back("visibility: on: some patch can block a pair of other patches");
    } else {
      e.visibility = false;
      e.reasons.push_back("visibility: off: no patch can block any pair of other patches (exact test)");
    }
  }
  e.cull_facing_away = true;
  e.reasons.push_back("facing away: pairs whose polygons face away from each other are skipped (factor 0)");
  return e;
}

}  // namespace hrad
