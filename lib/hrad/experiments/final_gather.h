// Final gather: the radiosity of a solved scene reconstructed at given points by one more bounce,
//   B(x) = E(x) + rho(x) * sum_j F(x -> j) V(x, j) B_j,
// over the leaves j of the solution, with Lambert's exact point-to-polygon factor and the fraction
// of leaf j visible from x. The piecewise-constant B_j enter only through an integral, so the
// result is far smoother and more accurate than B_j itself, and shadow boundaries are resolved at
// the points, not at the elements (Reichert 1992, "A two-pass radiosity method driven by lights and
// viewer position"; Lischinski, Tampieri & Greenberg 1993, "Combining hierarchical radiosity and
// discontinuity meshing"; Cohen & Wallace 1993, "Radiosity and realistic image synthesis", sec. 9.3).
// hrad uses it to make sweep references that no run shares (experiments/sweep.h): the leaf-by-leaf
// gather of gather/leaf_gather.h (tolerance 0, each partly visible leaf sampled on its own) at
// surface samples, times the reflectance.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "hrad/analysis/error_metrics.h"
#include "hrad/core/scene.h"
#include "hrad/core/solution.h"
#include "hrad/gather/final_gather.h"
#include "hrad/gather/link_gather.h"
#include "hrad/solvers/solved_hierarchy.h"

namespace hrad {

struct FinalGatherOptions {
  /// Barnes-Hut tolerance of the gather (gather/leaf_gather.h, gather/link_gather.h below each
  /// link's source); 0, every leaf on its own, for a reference.
  double tolerance = 0.0;
  /// Stratified points per leaf when the leaf is partly visible from x; leaves classified fully
  /// visible or hidden from x need none.
  int visibility_samples = 64;
  /// Rays per point of the gather through the links, shared by the point's partly visible sources
  /// (LinkGatherOptions::visibility_samples).
  int link_rays = LinkGatherOptions{}.visibility_samples;
  int threads = 0;  ///< 0 = all cores
  /// A hierarchical solve's hierarchy and links: gather through them (gather/link_gather.h) instead
  /// of over every patch; null (or another method's solve) gathers over every patch.
  const SolvedHierarchy* links = nullptr;
  /// Progress: (points done, points in all).
  std::function<void(std::size_t, std::size_t)> progress;
};

/// The reflected radiosity B(x) - E(x) at each point (samples on the scene's patches), gathered
/// from `solution`'s leaves (their face_radiosity, emission included), or through options.links. Deterministic. `work`,
/// when given, receives the gather's work.
std::vector<Rgb> final_gather_reflected(const Scene& scene, const Solution& solution,
                                        std::span<const SurfaceSample> points, const FinalGatherOptions& options,
                                        GatherWork* work = nullptr);

}  // namespace hrad
