// A small z-buffered software rasterizer: convex polygons (fan-triangulated) with
// perspective-correct interpolation of a per-vertex linear RGB value, and depth-tested segments.
// Values stay linear in the buffer; finish() maps them to 8-bit colour (tone map, colormap).
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "hrad/core/types.h"
#include "hrad/render/camera.h"
#include "hrad/render/image.h"

namespace hrad {

class Rasterizer {
 public:
  /// `near_distance` clips geometry closer than that to the camera plane; 0 picks
  /// 1e-6 * |target - position|.
  explicit Rasterizer(const Camera& camera, double near_distance = 0.0);

  /// Fills a planar convex polygon given in world space with one value per vertex. Pixels whose
  /// centre (x + 0.5, y + 0.5) is inside a triangle take the perspective-correct interpolation
  /// (Heckbert & Moreton 1991: interpolate value/z and 1/z linearly in screen space) if nearer
  /// than what the pixel holds.
  void fill_polygon(std::span<const Vec3> points, std::span<const Rgb> values);

  /// Walks a world-space segment in steps of at most one pixel and calls `plot(x, y)` for each
  /// pixel that is empty or whose depth is not smaller than the segment's by more than the
  /// relative tolerance `depth_bias` (so edges lying on a filled polygon show); a negative
  /// `depth_bias` skips the test. The buffers are not changed.
  void trace_segment(const Vec3& a, const Vec3& b, const std::function<void(int, int)>& plot,
                     double depth_bias = 2e-3) const;

  bool covered(int x, int y) const { return depth_[index(x, y)] < kFar; }
  double depth(int x, int y) const { return depth_[index(x, y)]; }
  const Rgb& value(int x, int y) const { return value_[index(x, y)]; }
  const Camera& camera() const { return camera_; }

  /// Covered pixels through `map`, the others `background`.
  Image finish(const std::function<Rgb8(const Rgb&)>& map, Rgb8 background) const;

 private:
  static constexpr double kFar = 1e300;
  std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * camera_.width + x; }
  struct ClipVertex {
    Vec3 cam;
    Rgb value;
  };
  void fill_triangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c);

  Camera camera_;
  double near_;
  std::vector<double> depth_;
  std::vector<Rgb> value_;
};

}  // namespace hrad
