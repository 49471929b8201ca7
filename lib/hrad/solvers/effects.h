// What a scene calls for: decided once before solving, so that solvers simulate only the effects
// that can change the answer (and `--effects all` checks that the shortcuts change nothing).
#pragma once

#include <string>
#include <vector>

#include "hrad/core/scene.h"

namespace hrad {

class Visibility;

enum class EffectsMode {
  kAuto,  ///< switch off what the scene provably does not need
  kAll,   ///< everything on: visibility, three channels, bounces, no culling of facing-away pairs
};

struct Effects {
  /// Ask the visibility oracle for each pair. Off when no patch can block any pair of other
  /// patches (Visibility::scene_has_occlusion(), exact predicates): then every factor is unoccluded.
  bool visibility = true;
  /// 1 when every reflectance and emission is gray (r == g == b exactly): solve channel 0 and copy.
  int color_channels = 3;
  /// Off when every reflectance is 0: then B = E and no form factor is needed.
  bool bounces = true;
  /// Skip pairs whose polygons face away from each other (their factor is exactly 0) without
  /// calling the kernel. On in auto mode; off with `--effects all` (the kernel then returns the 0).
  bool cull_facing_away = true;
  /// One line per decision, saying what and why ("visibility: off: no patch can block a pair ...").
  std::vector<std::string> reasons;
};

/// Analyses `scene`. In kAuto mode `visibility` must be the scene's oracle (it is asked
/// scene_has_occlusion()); it may be null in kAll mode or when the scene has no bounces.
/// `irradiance`: the gathered irradiance is wanted (SolveOptions::irradiance), so the factors are
/// needed even where nothing reflects: bounces stay on.
Effects analyse_effects(const Scene& scene, EffectsMode mode, const Visibility* visibility, bool irradiance = false);

/// True when every material's reflectance and emission have r == g == b exactly.
bool scene_is_gray(const Scene& scene);

/// True when every material's reflectance is 0 in every channel.
bool scene_has_no_reflection(const Scene& scene);

}  // namespace hrad
