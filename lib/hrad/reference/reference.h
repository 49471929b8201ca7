// hrad's independent ruler: Monte Carlo path tracing of a scene's radiosity, with a standard error
// on every number. It shares no kernel with the solvers (no form factor, no visibility oracle: its
// own ray casting on Embree, embree_scene.h), so a solver and the ruler agreeing is evidence, not
// an echo. It answers two questions:
//   - at probe points (a position and the direction its sensor faces, on a surface or anywhere in
//     the scene): the irradiance H, in exitance units (what a reflectance multiplies); and, for a
//     point on a patch's front, that patch's radiosity B = E + rho H;
//   - per input face (Scene::faces, a face may be several patches): the area-mean radiosity, from
//     stratified uniform points over the face, one path each.
// The physics and the estimator (next-event estimation toward the emitters drawn by power,
// cosine-weighted bounces, multiple importance sampling with the power heuristic, Russian
// roulette; Kajiya 1986, Veach 1997, Arvo & Kirk 1990) are stated in path_tracer.h.
//
// Standard errors: sqrt(sample variance of the per-path estimates / N). At points the N paths are
// independent, so the error is an estimate of the true standard deviation of the mean; over faces
// the points are stratified, which makes the true error smaller than the one reported (the
// stratified variance is below the plain one), so a bound of k standard errors is conservative.
//
// Deterministic: the paths of a query come in blocks of kPathsPerBlock, block b of query q seeded
// from (seed, q, b), and blocks are merged in order, so the result has the same bits at any thread
// count, and depends only on the scene, the queries, the options and the seed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "hrad/core/probe_point.h"
#include "hrad/core/progress.h"
#include "hrad/core/scene.h"
#include "hrad/core/types.h"
#include "hrad/geometry/front_patch.h"

namespace hrad {

struct ReferenceOptions {
  /// Paths per probe point; stratified points (one path each) per input face. At least 2 (a
  /// standard error needs two).
  int samples = 1024;
  /// Longest path in segments (1 = direct light only); 0 = no limit (Russian roulette ends paths
  /// without bias). A limit drops the light of longer paths.
  int max_depth = 0;
  /// Surfaces a path reflects from before Russian roulette starts (>= 1).
  int roulette_depth = 3;
  std::uint64_t seed = 1;
  /// Worker threads; 0 = TBB's default (all cores). The results do not depend on it.
  int threads = 0;
  /// Lines of progress for long runs (queries done of all, time elapsed, time left; at most one
  /// every 2 s, none for shorter runs: core/progress.h); may be empty.
  ProgressSink progress;
};

/// Paths per block (the unit of parallel work and of seeding).
inline constexpr int kPathsPerBlock = 64;

struct ReferenceSummary {
  std::uint64_t closest_hit_rays = 0;  ///< embree closest-hit queries (bounces)
  std::uint64_t shadow_rays = 0;       ///< embree occlusion queries (next-event estimation)
  std::uint64_t rays() const { return closest_hit_rays + shadow_rays; }
  std::uint64_t paths = 0;     ///< paths traced (faces that cannot reflect need none)
  double build_seconds = 0.0;  ///< building the BVH
  double trace_seconds = 0.0;  ///< tracing the paths
  double total_seconds = 0.0;
};

struct PointEstimate {
  Rgb irradiance = Rgb::Zero();     ///< H at the point facing its normal, exitance units
  Rgb irradiance_se = Rgb::Zero();  ///< its standard error
  /// The patch whose front the point lies on (front_patch_at), or -1 for a point in space.
  int patch = -1;
  Rgb radiosity = Rgb::Zero();     ///< E + rho H of that patch (0 when patch is -1)
  Rgb radiosity_se = Rgb::Zero();  ///< rho times irradiance_se
};

struct FaceEstimate {
  Rgb radiosity = Rgb::Zero();     ///< area mean over the face
  Rgb radiosity_se = Rgb::Zero();  ///< standard error (conservative: the points are stratified)
};

/// Throws hrad::Error naming the command-line option ("--samples must be >= 2, got 1").
void validate_reference_options(const ReferenceOptions& options);

/// Irradiance (and radiosity on patches) at each point. A point found on a patch's front
/// (front_patch_at with probe_tolerance) is moved onto the patch's plane and faces its normal.
/// Validates the options first.
ReferenceSummary reference_points(const Scene& scene, std::span<const ProbePoint> points,
                                  const ReferenceOptions& options, std::vector<PointEstimate>* out);

/// Area-mean radiosity of every input face (in Scene::faces order). Faces whose patches reflect
/// nothing are their emission exactly (standard error 0) and cost no path.
ReferenceSummary reference_faces(const Scene& scene, const ReferenceOptions& options, std::vector<FaceEstimate>* out);

}  // namespace hrad
