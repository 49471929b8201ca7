#include "hrad/render/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hrad {
namespace {

struct Frame {
  Vec3 right, up, forward;
};

Frame frame_of(const Camera& c) {
  const Vec3 forward = (c.target - c.position).normalized();
  const Vec3 right = forward.cross(c.up).normalized();
  return {right, right.cross(forward), forward};
}

}  // namespace

Vec3 to_camera(const Camera& camera, const Vec3& world) {
  const Frame f = frame_of(camera);
  const Vec3 d = world - camera.position;
  return {d.dot(f.right), d.dot(f.up), d.dot(f.forward)};
}

Vec3 camera_to_pixel(const Camera& camera, const Vec3& cam) {
  const double tan_half = std::tan(0.5 * camera.vfov_deg * std::numbers::pi / 180.0);
  const double aspect = static_cast<double>(camera.width) / camera.height;
  const double ndc_x = cam.x() / (cam.z() * tan_half * aspect);  // [-1, 1] across the image
  const double ndc_y = cam.y() / (cam.z() * tan_half);
  return {0.5 * (ndc_x + 1.0) * camera.width, 0.5 * (1.0 - ndc_y) * camera.height, cam.z()};
}

std::optional<Vec3> project(const Camera& camera, const Vec3& world) {
  const Vec3 cam = to_camera(camera, world);
  if (!(cam.z() > 0.0)) return std::nullopt;
  return camera_to_pixel(camera, cam);
}

Vec3 pixel_direction(const Camera& camera, double px, double py) {
  const Frame f = frame_of(camera);
  const double tan_half = std::tan(0.5 * camera.vfov_deg * std::numbers::pi / 180.0);
  const double aspect = static_cast<double>(camera.width) / camera.height;
  const double ndc_x = 2.0 * px / camera.width - 1.0, ndc_y = 1.0 - 2.0 * py / camera.height;
  return ndc_x * tan_half * aspect * f.right + ndc_y * tan_half * f.up + f.forward;
}

Camera cornell_box_camera(int width, int height) {
  Camera c;
  c.position = Vec3(278, 273, -800);
  c.target = Vec3(278, 273, 0);
  c.up = Vec3::UnitY();
  c.vfov_deg = 2.0 * std::atan(0.0125 / 0.035) * 180.0 / std::numbers::pi;
  c.width = width;
  c.height = height;
  return c;
}

Camera fit_camera(const Vec3& lo, const Vec3& hi, int width, int height, double vfov_deg) {
  const Vec3 centre = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * (hi - lo).norm(), 1e-12);
  Camera c;
  c.target = centre;
  c.up = Vec3::UnitY();
  c.vfov_deg = vfov_deg;
  c.width = width;
  c.height = height;
  const Vec3 direction = Vec3(0.3, 0.4, -1.0).normalized();
  // The nearest distance at which every box corner lies within 95% of the image half-extents:
  // corner k at (x_k, y_k, z_k) in the camera frame centred on the box needs
  // |x_k| <= 0.95 tan(half) aspect (D + z_k), and the same for y without the aspect.
  c.position = centre + direction;
  const double tan_half = std::tan(0.5 * vfov_deg * std::numbers::pi / 180.0);
  const double aspect = static_cast<double>(width) / height;
  double distance = 1e-3 * radius;
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
    const Vec3 q = to_camera(c, corner) - to_camera(c, centre);
    distance = std::max({distance, std::abs(q.x()) / (0.95 * tan_half * aspect) - q.z(),
                         std::abs(q.y()) / (0.95 * tan_half) - q.z(), 1e-3 * radius - q.z()});
  }
  c.position = centre + distance * direction;
  return c;
}

}  // namespace hrad
