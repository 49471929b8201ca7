// The Monte Carlo reference's own ray caster: the scene's patches as triangles in an Embree 3 BVH
// (Wald, Woop, Benthin, Johnson & Ernst 2014, "Embree: a kernel framework for efficient CPU ray
// tracing", ACM TOG 33(4)). It shares nothing with hrad's visibility module (CGAL, exact
// predicates), so that the reference and the solvers cannot agree on a shared mistake.
//
// Embree intersects in single precision; hit points are projected back onto the hit patch's
// plane in double precision. A ray never counts a hit on a patch whose plane passes through its
// origin (or, for a segment, its end): a ray leaving a point of a plane meets that plane only at
// the point itself (unless it runs inside the plane, a set of measure zero), so the rule removes
// self-hits and hits on coplanar neighbours (back-to-back walls, T-junction pieces) exactly, with
// a tolerance only for rounding (plane_tolerance()), and no offset of ray origins.
#pragma once

#include <cstdint>
#include <memory>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"

namespace hrad {

/// Rays cast, counted where they are cast (one embree call each).
struct RayCounts {
  std::uint64_t closest_hit = 0;  ///< rtcIntersect1: the first patch along a ray
  std::uint64_t shadow = 0;       ///< rtcOccluded1: is a segment blocked?
  std::uint64_t total() const { return closest_hit + shadow; }
  RayCounts& operator+=(const RayCounts& o) {
    closest_hit += o.closest_hit;
    shadow += o.shadow;
    return *this;
  }
};

/// The first patch along a ray.
struct RayHit {
  int patch = -1;             ///< index into Scene::patches; -1 when the ray leaves the scene
  bool front = false;         ///< the ray arrived at the patch's front (its normal faces the ray's origin)
  Vec3 point = Vec3::Zero();  ///< the hit, on the patch's plane to double rounding
};

class EmbreeScene {
 public:
  /// Builds the BVH of `scene`'s patches (each a fan of triangles). The scene must outlive this.
  /// Throws hrad::Error if Embree fails (no device, out of memory).
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// The first patch hit by the ray from `origin` along the unit vector `direction`, ignoring
  /// patches whose plane passes through `origin`. Where two patches lie back to back (a wall of
  /// zero thickness) the ray meets the one facing it: a back hit costs a second ray that looks for
  /// a front in the same plane. Thread-safe.
  RayHit closest_hit(const Vec3& origin, const Vec3& direction, RayCounts& counts) const;

  /// Whether a patch blocks the segment from `a` to `b`, ignoring patches whose plane passes
  /// through `a` or `b` (a segment ending on a patch is not blocked by it). Thread-safe.
  bool blocked(const Vec3& a, const Vec3& b, RayCounts& counts) const;

  /// Largest distance of a point from a plane that still counts as on it: 1e-9 of the scene's
  /// size (its largest coordinate or its bounding box's diagonal, whichever is larger), far above
  /// the rounding of a projected hit point and far below any feature a scene file can state.
  double plane_tolerance() const;

  const Scene& scene() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace hrad
