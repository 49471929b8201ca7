#include "hrad/render/rasterizer.h"

#include <algorithm>
#include <cmath>

#include "hrad/render/pixel_samples.h"

namespace hrad {

Rasterizer::Rasterizer(const Camera& camera, double near_distance, int pass, int passes, std::uint64_t seed)
    : camera_(camera),
      near_(near_distance > 0.0 ? near_distance : 1e-6 * (camera.target - camera.position).norm()),
      pass_(pass),
      passes_(passes),
      seed_(seed),
      depth_(static_cast<std::size_t>(camera.width) * camera.height, kFar),
      value_(static_cast<std::size_t>(camera.width) * camera.height, Rgb::Zero()),
      id_(static_cast<std::size_t>(camera.width) * camera.height, -1) {}

Vec2 Rasterizer::sample_position(int x, int y) const {
  return pass_ < 0 ? Vec2(x + 0.5, y + 0.5) : pixel_sample(x, y, pass_, passes_, seed_);
}

void Rasterizer::fill_polygon(std::span<const Vec3> points, std::span<const Rgb> values, int id) {
  // Clip the polygon to the half-space depth >= near in camera space (Sutherland-Hodgman), which
  // keeps it convex, then fan-triangulate.
  std::vector<ClipVertex> in, out;
  for (std::size_t i = 0; i < points.size(); ++i) in.push_back({to_camera(camera_, points[i]), values[i]});
  for (std::size_t i = 0; i < in.size(); ++i) {
    const ClipVertex& p = in[i];
    const ClipVertex& q = in[(i + 1) % in.size()];
    const bool p_in = p.cam.z() >= near_, q_in = q.cam.z() >= near_;
    if (p_in) out.push_back(p);
    if (p_in != q_in) {
      const double t = (near_ - p.cam.z()) / (q.cam.z() - p.cam.z());
      out.push_back({p.cam + t * (q.cam - p.cam), p.value + t * (q.value - p.value)});
    }
  }
  for (std::size_t i = 1; i + 1 < out.size(); ++i) fill_triangle(out[0], out[i], out[i + 1], id);
}

void Rasterizer::fill_triangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c, int id) {
  const Vec3 p[3] = {camera_to_pixel(camera_, a.cam), camera_to_pixel(camera_, b.cam), camera_to_pixel(camera_, c.cam)};
  const Rgb* v[3] = {&a.value, &b.value, &c.value};
  auto edge = [](const Vec3& s, const Vec3& t, double x, double y) {
    return (t.x() - s.x()) * (y - s.y()) - (t.y() - s.y()) * (x - s.x());
  };
  const double area = edge(p[0], p[1], p[2].x(), p[2].y());
  if (!(std::abs(area) > 1e-12)) return;  // edge-on or degenerate: covers no pixel centre
  const double w[3] = {1.0 / p[0].z(), 1.0 / p[1].z(), 1.0 / p[2].z()};
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].x(), p[1].x(), p[2].x()}))));
  const int x1 = std::min(camera_.width - 1, static_cast<int>(std::ceil(std::max({p[0].x(), p[1].x(), p[2].x()}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p[0].y(), p[1].y(), p[2].y()}))));
  const int y1 = std::min(camera_.height - 1, static_cast<int>(std::ceil(std::max({p[0].y(), p[1].y(), p[2].y()}))));
  constexpr double tol = -1e-9;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Vec2 sample = sample_position(x, y);
      const double px = sample.x(), py = sample.y();
      const double l0 = edge(p[1], p[2], px, py) / area;
      const double l1 = edge(p[2], p[0], px, py) / area;
      const double l2 = 1.0 - l0 - l1;
      if (l0 < tol || l1 < tol || l2 < tol) continue;
      const double winv = l0 * w[0] + l1 * w[1] + l2 * w[2];
      const double z = 1.0 / winv;
      const std::size_t i = index(x, y);
      if (!(z < depth_[i])) continue;
      depth_[i] = z;
      value_[i] = (l0 * w[0] * *v[0] + l1 * w[1] * *v[1] + l2 * w[2] * *v[2]) / winv;
      id_[i] = id;
    }
  }
}

void Rasterizer::trace_segment(const Vec3& a, const Vec3& b, const std::function<void(int, int)>& plot,
                               double depth_bias) const {
  Vec3 ca = to_camera(camera_, a), cb = to_camera(camera_, b);
  if (ca.z() < near_ && cb.z() < near_) return;
  if (ca.z() < near_) ca = ca + (near_ - ca.z()) / (cb.z() - ca.z()) * (cb - ca);
  if (cb.z() < near_) cb = cb + (near_ - cb.z()) / (ca.z() - cb.z()) * (ca - cb);
  const Vec3 pa = camera_to_pixel(camera_, ca), pb = camera_to_pixel(camera_, cb);
  const double length = std::max(std::abs(pb.x() - pa.x()), std::abs(pb.y() - pa.y()));
  if (!std::isfinite(length)) return;
  // Screen-space steps of at most one pixel; clamp the walk to the image's neighbourhood.
  const int steps = static_cast<int>(std::min(std::ceil(length), 4.0 * (camera_.width + camera_.height))) + 1;
  for (int s = 0; s <= steps; ++s) {
    const double t = static_cast<double>(s) / steps;
    const double x = pa.x() + t * (pb.x() - pa.x()), y = pa.y() + t * (pb.y() - pa.y());
    const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
    if (ix < 0 || iy < 0 || ix >= camera_.width || iy >= camera_.height) continue;
    const double z = 1.0 / ((1.0 - t) / pa.z() + t / pb.z());  // 1/z is linear in screen space
    const std::size_t i = index(ix, iy);
    if (depth_bias >= 0.0 && depth_[i] < kFar && z > depth_[i] * (1.0 + depth_bias)) continue;
    plot(ix, iy);
  }
}

Image Rasterizer::finish(const std::function<Rgb8(const Rgb&)>& map, Rgb8 background) const {
  Image image(camera_.width, camera_.height, background);
  for (int y = 0; y < camera_.height; ++y)
    for (int x = 0; x < camera_.width; ++x)
      if (covered(x, y)) image.at(x, y) = map(value(x, y));
  return image;
}

}  // namespace hrad
