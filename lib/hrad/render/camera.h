// A pinhole camera: position, look-at point, up vector, vertical field of view, image size.
// Camera frame: forward = normalize(target - position), right = normalize(forward x up),
// true_up = right x forward (so a right-handed world is seen without mirroring).
// Pixel coordinates: x to the right, y down, pixel (i, j) covers [i, i+1) x [j, j+1).
#pragma once

#include <optional>

#include "hrad/core/types.h"

namespace hrad {

struct Camera {
  Vec3 position = Vec3::Zero();
  Vec3 target = Vec3::UnitZ();
  Vec3 up = Vec3::UnitY();
  double vfov_deg = 40.0;  ///< full vertical field of view, degrees
  int width = 512;
  int height = 512;
};

/// Camera-space coordinates of a world point: (right, up, forward distance).
Vec3 to_camera(const Camera& camera, const Vec3& world);

/// Pixel position (x, y) and depth (forward distance) of a camera-space point with depth > 0.
Vec3 camera_to_pixel(const Camera& camera, const Vec3& cam);

/// World point -> (pixel x, pixel y, depth); empty when the point is not in front of the camera.
std::optional<Vec3> project(const Camera& camera, const Vec3& world);

/// The world direction (not normalised; unit length along the viewing direction) from the camera
/// through the image point (px, py) in pixel coordinates: the inverse of project().
Vec3 pixel_direction(const Camera& camera, double px, double py);

/// The Cornell box camera (Cornell University Program of Computer Graphics, "Cornell Box Data"):
/// at (278, 273, -800) looking along +z with +y up, focal length 0.035 and a 0.025 x 0.025 film,
/// so the vertical field of view is 2 atan(0.0125 / 0.035) = 39.3076 degrees.
Camera cornell_box_camera(int width = 512, int height = 512);

/// A camera that sees the whole axis-aligned box [lo, hi]: it looks at the box centre from the
/// direction (0.3, 0.4, -1) (the Cornell view, slightly from above and the side), from the nearest
/// distance at which all eight corners fall within 95% of the image's half-width and half-height.
Camera fit_camera(const Vec3& lo, const Vec3& hi, int width = 512, int height = 512, double vfov_deg = 40.0);

}  // namespace hrad
