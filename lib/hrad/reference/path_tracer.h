// One Monte Carlo path: an unbiased estimate of the irradiance at a point facing a direction, in
// the exitance units hrad uses (what a surface's reflectance multiplies).
//
// On Lambertian surfaces the radiance leaving y is L(y) = B(y) / pi, with B the radiosity (an
// exitance, like the emission E). The irradiance at x facing n is
//   H(x) = int_hemisphere L_in cos(theta) dw = (1/pi) int_hemisphere B(y(x, w)) cos(theta) dw,
// y(x, w) the first surface along w, B counted only where w arrives at a front (a back is black),
// and B(y) = E(y) + rho(y) H(y) (Kajiya 1986, "The rendering equation", in radiosity form). In a
// closed room of uniform E and rho this gives H = B = E / (1 - rho).
//
// The path estimates H(x0) recursively with the throughput T (T = 1 at x0, T *= rho at every
// surface it continues from), at each vertex x with normal n:
//   - next-event estimation: an emitter patch k drawn with probability proportional to its power
//     A_k (E_r + E_g + E_b), a point y uniform on it (density p_A = P(k) / A_k); unless a patch
//     blocks the segment, T E_k (cos_x / pi) / p_light weighted by the power heuristic, with
//     p_light = p_A r^2 / cos_y (the light sample's density per solid angle);
//   - a bounce: a direction drawn with density p_bsdf = cos_x / pi (Malley's method), so that a
//     hit on an emitter's front adds T E_j weighted by the power heuristic against p_light;
//   - multiple importance sampling by the power heuristic, w_s = p_s^2 / (p_light^2 + p_bsdf^2)
//     (Veach 1997, "Robust Monte Carlo methods for light transport simulation", PhD thesis,
//     Stanford, sec. 9.2.4): the two strategies' weights sum to 1 on every direction, so the sum is
//     unbiased for any mix of small and large emitters;
//   - Russian roulette from `roulette_depth` surfaces on: the path continues with probability
//     q = max_c rho_c(y) and T is divided by q (Arvo & Kirk 1990, "Particle transport and image
//     synthesis"), which keeps the estimate unbiased while ending paths with probability 1.
// A path ends when its ray leaves the scene (open scenes), arrives at a patch's back, at a black
// surface, by the roulette, or after `max_depth` segments (0: no limit; a limit drops the light of
// longer paths, a bias the caller chose).
#pragma once

#include <vector>

#include "hrad/core/rng.h"
#include "hrad/core/scene.h"
#include "hrad/reference/area_sampler.h"
#include "hrad/reference/embree_scene.h"

namespace hrad::detail {

/// A direction with density cos(theta) / pi about the unit normal n (Malley's method).
Vec3 cosine_direction(const Vec3& n, Rng& rng);

class PathTracer {
 public:
  PathTracer(const EmbreeScene& rays, int max_depth, int roulette_depth);

  /// One path's estimate of H(x) at x facing the unit normal n. Rays from x ignore patches whose
  /// plane passes through x (a point on a patch sees past it).
  Rgb irradiance(const Vec3& x, const Vec3& n, Rng& rng, RayCounts& counts) const;

  const EmbreeScene& rays() const { return rays_; }

 private:
  const EmbreeScene& rays_;
  const Scene& scene_;
  int max_depth_;
  int roulette_depth_;
  AreaSampler emitters_;  ///< emitter patches, drawn by power
  std::vector<Rgb> reflectance_, emission_;
};

}  // namespace hrad::detail
