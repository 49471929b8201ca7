// Points of a convex polygon distributed uniformly in the solid angle it subtends at a point, for
// sampled visibility between surfaces closer than their size. No CGAL here.
#pragma once

#include <span>

#include <boost/container/small_vector.hpp>

#include "hrad/core/types.h"

namespace hrad::detail {

/// Maps the unit square onto the spherical polygon that a convex planar polygon subtends at `x`,
/// uniformly by solid angle, and returns the point of the polygon along that direction. u picks a
/// triangle of the fan from vertex 0 (by solid angle) and is remapped into it; within a triangle,
/// Arvo's area-preserving map (Arvo 1995, "Stratified sampling of spherical triangles"). So a
/// polygon's point-to-point kernel cos(theta_x) cos(theta_y) / r^2 dA becomes cos(theta_x) dOmega:
/// where the polygon comes within a hair of x, the samples follow the kernel instead of leaving
/// its peak to chance. The polygon must lie wholly in front of x (no vertex on or behind a plane
/// through x; callers clip to the half-space in front of x's tangent plane).
class SolidAngleSampler {
 public:
  SolidAngleSampler(const Vec3& x, std::span<const Vec3> polygon);
  /// The solid angle the polygon subtends at x (0 when it is seen edge-on).
  double solid_angle() const { return solid_angle_; }
  /// The unit direction from x and the polygon's point along it; false when no point is found
  /// (solid angle 0, or a direction that rounding left parallel to the polygon's plane).
  bool sample(double u, double v, Vec3* direction, Vec3* point) const;

 private:
  struct Triangle {
    Vec3 a, b, c;         ///< unit directions from x to the fan triangle's corners
    double alpha = 0.0;   ///< the spherical triangle's angle at a
    double cos_ab = 0.0;  ///< cosine of the arc from a to b
    double solid_angle = 0.0;
  };
  Vec3 x_;
  Vec3 normal_;          ///< the polygon's unit normal
  double offset_ = 0.0;  ///< normal_ . (vertex - x): the plane's signed distance from x
  boost::container::small_vector<Triangle, 2> triangles_;
  double solid_angle_ = 0.0;
};

}  // namespace hrad::detail
