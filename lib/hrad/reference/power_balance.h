// Where a solution's power goes, checked with the reference's own rays (embree_scene.h), so that a
// solver cannot hide a loss behind its own factors.
//
// In an exact solution every watt that leaves a surface (sum over elements of A B) lands somewhere:
// on the front of a reflecting surface (irradiance H, of which (1 - rho) H is absorbed and rho H
// leaves again, B = E + rho H), on the front of a black surface (absorbed), on a back (hrad's
// surfaces are one-sided: lost) or nowhere (it escapes through an opening). Hence
//   emitted = absorbed by reflecting surfaces + absorbed by black ones + onto backs + escaped,
// with the first term known exactly from B (A (1 - rho) / rho (B - E) per element and channel) and
// the last three estimated by casting the solution's own light: a leaf drawn by its power A B, a
// point uniform on it, a cosine-distributed direction, and where the ray first lands (Kajiya 1986:
// the radiance leaving a Lambertian surface is B / pi). Their sum is the residual's partner: the
// residual emitted - (all four) is 0 for an exact solution, whatever the scene, and measures the
// power a solver lost or made (its factors' closure and reciprocity errors, an unconverged
// iteration). In a closed scene no ray escapes, so the sampled terms are exactly 0 when every
// surface reflects and the residual is exact.
#pragma once

#include <cstdint>

#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/core/types.h"

namespace hrad {

/// The residual allowed, as a share of the emitted power, beyond kPowerBalanceStandardErrors
/// standard errors of the sampled terms.
inline constexpr double kPowerBalanceTolerance = 1e-3;
inline constexpr double kPowerBalanceStandardErrors = 4.0;

struct PowerBalanceOptions {
  int rays = 1 << 16;  ///< rays cast from the solution's light (0: no sampled terms)
  std::uint64_t seed = 1;
};

/// Per colour channel, in the scene's power units (area times exitance).
struct PowerBalance {
  Rgb emitted = Rgb::Zero();              ///< sum of A E over patches
  Rgb leaving = Rgb::Zero();              ///< sum of A B over leaves
  Rgb absorbed_reflecting = Rgb::Zero();  ///< sum of A (1 - rho) / rho (B - E) over leaves with rho > 0
  Rgb absorbed_black = Rgb::Zero();       ///< sampled: landing on the front of a surface with rho = 0
  Rgb onto_backs = Rgb::Zero();           ///< sampled: landing on a surface's back
  Rgb escaped = Rgb::Zero();              ///< sampled: leaving the scene
  Rgb sampled_se = Rgb::Zero();           ///< standard error of the three sampled terms' sum
  /// emitted - absorbed_reflecting - absorbed_black - onto_backs - escaped.
  Rgb residual = Rgb::Zero();
  std::uint64_t rays = 0;  ///< rays cast (each one embree closest-hit query or two)

  /// Largest |residual| / emitted over the channels that emit (0 if none does).
  double relative_residual() const;
  /// kPowerBalanceTolerance plus kPowerBalanceStandardErrors sampled_se, relative to emitted, in
  /// the channel of relative_residual().
  double allowed() const;
  bool balanced() const { return relative_residual() <= allowed(); }
};

/// The power balance of `solution` (leaves of `scene`). Deterministic for a seed.
PowerBalance power_balance(const Scene& scene, const Solution& solution, const PowerBalanceOptions& options = {});

}  // namespace hrad
