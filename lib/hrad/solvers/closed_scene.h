// Whether a solve's light stays in its scene, so that what every element sends may be closed.
//
// In a scene that keeps its light (no opening, no surface's back in sight of a front) every point's
// sends reach fronts of patches: its closure is 1 (Siegel & Howell, "Thermal Radiation Heat
// Transfer", the enclosure summation rule). A solve's links only estimate that sum: their sampled
// visibility makes each leaf's closure a random variable, and the room's power balance the sum of
// those errors weighed by the leaves' power, zero-mean noise of about 7e-4 to 1e-3 of the emitted
// power at the default sampling however many links there are (--power-noise). Where the light stays
// in the scene, send_closures() closes each leaf's sends to exactly 1, a row-sum closure as
// enclosures' view-factor matrices are closed (van Leersum 1989, viewfactors/closure.h): the power
// balances to the iteration's tolerance by construction, and no receiver's share changes by more
// than its links' own error.
//
// Whether it stays is decided by the solve's own light: N rays leave the leaves drawn by their
// power A B, from a point uniform on the leaf along a cosine-distributed direction (what a
// Lambertian surface sends), and count as lost where they leave the scene or meet a back. Closing
// a scene that loses a share l of its leaving power P makes l P. So the scene counts as closed when
// the lost rays' share, times P over the emitted power, is at most kClosureLoss: a scene that loses
// a few rays in a hundred thousand (a hairline crack between rounded coordinates) is closed, one
// with an opening or a back in sight is not. With N = kClosureTestRaysPerLeavingPower P / emitted rays the lost rays
// are Poisson of mean l N, and the power closing makes on average, l P P(at most kClosureLoss N
// emitted / P lost), is at most 3.81 / kClosureTestRaysPerLeavingPower = 5.8e-5 of the emitted
// power (3.81: the largest of lambda P(Poisson(lambda) <= 6) over lambda, at 5; where the rays reach
// their bound it grows with P / emitted).
#pragma once

#include <cstdint>
#include <span>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"
#include "hrad/mesh/element_hierarchy.h"
#include "hrad/visibility/visibility.h"

namespace hrad {

/// The most power, as a share of the emitted power, that the lost rays may stand for in a scene
/// taken as closed.
inline constexpr double kClosureLoss = 1e-4;
/// Rays per unit of the leaving power over the emitted (closed_scene.h).
inline constexpr double kClosureTestRaysPerLeavingPower = 65536.0;
/// The fewest and the most rays the test casts.
inline constexpr std::uint64_t kLeastClosureTestRays = 1 << 16;
inline constexpr std::uint64_t kMostClosureTestRays = 1 << 22;

/// What the test plans: its rays and the lost rays it allows.
struct ClosureTestPlan {
  std::uint64_t rays = 0;
  std::uint64_t allowed_lost = 0;
};
/// The plan for a scene whose leaves send `leaving` (sum of A B) and whose patches emit `emitted`
/// (sum of A E): kClosureTestRaysPerLeavingPower times their ratio, within the bounds above, and
/// the lost rays whose share of that ratio is kClosureLoss.
ClosureTestPlan closure_test_plan(double leaving, double emitted);

struct LightLoss {
  std::uint64_t rays = 0;          ///< rays cast (each one Visibility::first_hit())
  std::uint64_t lost = 0;          ///< of them: leaving the scene or meeting a patch's back
  std::uint64_t allowed_lost = 0;  ///< the plan's
  bool own_visibility = false;     ///< cast with an oracle of its own (test_light_loss())
  bool closed() const { return rays > 0 && lost <= allowed_lost; }
};

/// Casts up to `plan.rays` rays from the leaves of `h`, drawn by A times the sum of `radiosity` (by
/// node id) over the channels, in batches of 4,096 (parallel, deterministic in `seed`); stops after
/// the batch in which more than `plan.allowed_lost` are lost.
LightLoss light_loss(const Scene& scene, const ElementHierarchy& h, std::span<const Rgb> radiosity,
                     const Visibility& visibility, const ClosureTestPlan& plan, std::uint64_t seed);

/// light_loss() of a solution (`radiosity` by node id) by the plan for its leaves' power and the
/// scene's emission, cast with `visibility`, or where that is null (a solve that needs no
/// visibility: nothing can block) with an oracle made for it.
LightLoss test_light_loss(const Scene& scene, const ElementHierarchy& h, std::span<const Rgb> radiosity,
                          const Visibility* visibility, std::uint64_t seed);

}  // namespace hrad
