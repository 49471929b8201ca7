// Points drawn on a set of patches: a patch with probability proportional to its area times a
// weight per unit area, then a point uniform on it. The emitters are drawn by power this way
// (weight = emitted exitance), an input face's points by area (weight 1).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "hrad/core/scene.h"
#include "hrad/core/types.h"

namespace hrad::detail {

struct SurfacePoint {
  Vec3 point = Vec3::Zero();  ///< on the patch's plane
  int patch = -1;
};

class AreaSampler {
 public:
  AreaSampler() = default;
  /// The patches `patches` of `scene`, patch p weighted by weight_per_area[p] (indexed by patch,
  /// sized like scene.patches); patches with weight 0 are never drawn.
  AreaSampler(const Scene& scene, std::span<const int> patches, std::span<const double> weight_per_area);

  bool empty() const { return cdf_.empty() || !(total_ > 0.0); }

  /// The point for (u, v) uniform in [0, 1)^2: u picks a triangle of the patches' fans by weight
  /// and is stretched over it, then the square-root warp maps (u, v) into the triangle (Turk 1990,
  /// "Generating random points in triangles", Graphics Gems). Stratified (u, v) stay stratified.
  SurfacePoint sample(double u, double v) const;

  /// Probability density per unit area of drawing a given point of `patch`.
  double density(int patch) const { return weight_per_area_[static_cast<std::size_t>(patch)] / total_; }

 private:
  struct Triangle {
    Vec3 a, ab, ac;  ///< a point is a + s ab + t ac: a coordinate constant over a wall stays exact
    int patch;
  };
  std::vector<Triangle> triangles_;
  std::vector<double> cdf_;  ///< cumulative weight, ending at total_
  std::vector<double> weight_per_area_;
  std::vector<Vec3> normal_;
  std::vector<double> offset_;
  double total_ = 0.0;
};

}  // namespace hrad::detail
