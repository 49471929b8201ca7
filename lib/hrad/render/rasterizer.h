// A small z-buffered software rasterizer: convex polygons (fan-triangulated) with
// perspective-correct interpolation of a per-vertex linear RGB value and a polygon id, and
// depth-tested segments. Values stay linear in the buffer; finish() maps them to 8-bit colour
// (tone map, colormap). Each pixel is sampled at one point: its centre, or for antialiasing a
// jittered point of one stratum of the pixel per pass (pixel_samples.h).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "hrad/core/image.h"
#include "hrad/core/types.h"
#include "hrad/render/camera.h"

namespace hrad {

class Rasterizer {
 public:
  /// `near_distance` clips geometry closer than that to the camera plane; 0 picks
  /// 1e-6 * |target - position|. With `pass` >= 0, pixel (x, y) is sampled at
  /// pixel_sample(x, y, pass, passes, seed) instead of its centre.
  explicit Rasterizer(const Camera& camera, double near_distance = 0.0, int pass = -1, int passes = 1,
                      std::uint64_t seed = 0);

  /// Fills a planar convex polygon given in world space with one value per vertex. Pixels whose
  /// sample point (the centre (x + 0.5, y + 0.5) unless jittered) is inside a triangle take the
  /// perspective-correct interpolation (Heckbert & Moreton 1991: interpolate value/z and 1/z
  /// linearly in screen space) and `id` if nearer than what the pixel holds.
  void fill_polygon(std::span<const Vec3> points, std::span<const Rgb> values, int id = -1);

  /// Walks a world-space segment in steps of at most one pixel and calls `plot(x, y)` for each
  /// pixel that is empty or whose depth is not smaller than the segment's by more than the
  /// relative tolerance `depth_bias` (so edges lying on a filled polygon show); a negative
  /// `depth_bias` skips the test. The buffers are not changed.
  void trace_segment(const Vec3& a, const Vec3& b, const std::function<void(int, int)>& plot,
                     double depth_bias = 2e-3) const;

  bool covered(int x, int y) const { return depth_[index(x, y)] < kFar; }
  double depth(int x, int y) const { return depth_[index(x, y)]; }
  const Rgb& value(int x, int y) const { return value_[index(x, y)]; }
  /// The id of the polygon seen at the pixel's sample (-1 where none, or none was given).
  int id(int x, int y) const { return id_[index(x, y)]; }
  /// Where pixel (x, y) is sampled, in pixel coordinates.
  Vec2 sample_position(int x, int y) const;
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
  void fill_triangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c, int id);

  Camera camera_;
  double near_;
  int pass_, passes_;
  std::uint64_t seed_;
  std::vector<double> depth_;
  std::vector<Rgb> value_;
  std::vector<int> id_;
};

}  // namespace hrad
