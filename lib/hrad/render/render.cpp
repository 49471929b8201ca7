#include "hrad/render/render.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "hrad/core/face_geometry.h"
#include "hrad/core/tone_map.h"
#include "hrad/render/rasterizer.h"

namespace hrad {
namespace {

/// Fills every (front-facing) face; `value_of(f, k)` gives the value of face f's k-th vertex.
template <class ValueOf>
void fill_faces(Rasterizer& r, const Solution& s, const RenderOptions& o, ValueOf value_of) {
  std::vector<Vec3> points;
  std::vector<Rgb> values;
  ProgressReporter progress("render", s.faces.size(), "elements", o.progress);
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    progress.advance();
    if (o.cull_back_faces && !faces_camera(s, f, o.camera)) continue;
    points.clear();
    values.clear();
    for (std::size_t k = 0; k < s.faces[f].size(); ++k) {
      points.push_back(s.vertices[s.faces[f][k]]);
      values.push_back(value_of(f, k));
    }
    r.fill_polygon(points, values);
  }
  progress.finish();
}

void draw_edges(const Rasterizer& r, const Solution& s, const RenderOptions& o, Image& image, Rgb8 colour) {
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (o.cull_back_faces && !faces_camera(s, f, o.camera)) continue;
    const std::vector<int>& face = s.faces[f];
    for (std::size_t k = 0; k < face.size(); ++k)
      r.trace_segment(s.vertices[face[k]], s.vertices[face[(k + 1) % face.size()]],
                      [&](int x, int y) { image.at(x, y) = colour; });
  }
}

// 3x5 glyphs, one row per 3 bits (msb = left column), top row first.
int glyph_row(char c, int row) {
  static const std::pair<char, std::array<int, 5>> glyphs[] = {
      {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
      {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
      {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'-', {0, 0, 7, 0, 0}},
      {'+', {0, 2, 7, 2, 0}}, {'e', {7, 4, 7, 4, 7}}, {'E', {7, 4, 7, 4, 7}}, {'%', {5, 1, 2, 4, 5}},
      {'l', {2, 2, 2, 2, 2}}, {'x', {0, 0, 5, 2, 5}}};
  for (const auto& [ch, rows] : glyphs)
    if (ch == c) return rows[row];
  return 0;
}

}  // namespace

bool faces_camera(const Solution& s, std::size_t f, const Camera& camera) {
  const Vec3 n = face_vector_area(s, f);
  return n.dot(camera.position - s.vertices[s.faces[f][0]]) > 0.0;
}

PixelAverager::PixelAverager(int width, int height, int samples_per_pixel, double exposure, Rgb8 background)
    : width_(width),
      height_(height),
      samples_(samples_per_pixel),
      exposure_(exposure),
      background_(background),
      value_sum_(static_cast<std::size_t>(width) * height, Rgb::Zero()),
      display_sum_(static_cast<std::size_t>(width) * height, Rgb::Zero()),
      covered_(static_cast<std::size_t>(width) * height, 0) {}

void PixelAverager::add(int x, int y, const Rgb& value) {
  const std::size_t i = static_cast<std::size_t>(y) * width_ + x;
  const Rgb v = value.isFinite().select(value, Rgb::Zero());
  value_sum_[i] += v;
  display_sum_[i] += (exposure_ * v).min(1.0).max(0.0);
  ++covered_[i];
}

Image PixelAverager::display() const {
  Image image(width_, height_);
  Rgb background;
  for (int c = 0; c < 3; ++c) background[c] = srgb_decode(background_[c] / 255.0);
  for (std::size_t i = 0; i < display_sum_.size(); ++i) {
    const int missing = std::max(0, samples_ - covered_[i]);
    const Rgb mean = (display_sum_[i] + missing * background) / std::max(samples_, covered_[i]);
    for (int c = 0; c < 3; ++c)
      image.pixels[i][c] = static_cast<std::uint8_t>(std::lround(255.0 * srgb_encode(mean[c])));
  }
  return image;
}

HdrImage PixelAverager::linear() const {
  HdrImage image(width_, height_);
  for (std::size_t i = 0; i < value_sum_.size(); ++i) image.pixels[i] = value_sum_[i] / std::max(samples_, covered_[i]);
  return image;
}

std::pair<Vec3, Vec3> solution_bounds(const Solution& solution) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& v : solution.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  if (solution.vertices.empty()) lo = hi = Vec3::Zero();
  return {lo, hi};
}

Camera default_camera(const Solution& solution, int width, int height) {
  const auto [lo, hi] = solution_bounds(solution);
  const bool cornell = (lo.array() >= -1.0).all() && (hi.array() <= 560.0).all() && ((hi - lo).array() > 500.0).all();
  return cornell ? cornell_box_camera(width, height) : fit_camera(lo, hi, width, height);
}

RenderedImage render_solution_with_linear(const Solution& s, const RenderOptions& o) {
  const int passes = std::max(1, o.samples_per_pixel);
  PixelAverager average(o.camera.width, o.camera.height, passes, o.exposure, o.background);
  RenderOptions pass = o;
  if (passes > 1) pass.progress = {};  // one line per pass would repeat itself
  for (int k = 0; k < passes; ++k) {
    Rasterizer r(o.camera, 0.0, passes > 1 ? k : -1, passes, o.seed);
    fill_faces(r, s, pass, [&](std::size_t f, std::size_t i) { return s.vertex_radiosity[s.faces[f][i]]; });
    for (int y = 0; y < o.camera.height; ++y)
      for (int x = 0; x < o.camera.width; ++x)
        if (r.covered(x, y)) average.add(x, y, r.value(x, y));
  }
  return {average.display(), average.linear()};
}

Image render_solution(const Solution& s, const RenderOptions& o) { return render_solution_with_linear(s, o).display; }

Image render_wireframe(const Solution& s, const RenderOptions& o, const WireframeOptions& w) {
  Rasterizer r(o.camera);
  fill_faces(r, s, o, [&](std::size_t f, std::size_t) { return s.face_radiosity[f]; });
  Image image = r.finish([&](const Rgb& b) { return tone_map(b, o.exposure); }, o.background);
  draw_edges(r, s, o, image, w.edge_colour);
  for (const auto& [a, b] : w.links) r.trace_segment(a, b, [&](int x, int y) { image.at(x, y) = w.link_colour; });
  return image;
}

Rgb8 error_colormap(double t) {
  if (std::isnan(t)) return {128, 128, 128};
  t = std::clamp(t, 0.0, 1.0);
  const Rgb blue(59, 76, 192), white(221, 221, 221), red(180, 4, 38);
  const Rgb c = t < 0.5 ? Rgb(blue + 2.0 * t * (white - blue)) : Rgb(white + (2.0 * t - 1.0) * (red - white));
  return {static_cast<std::uint8_t>(std::lround(c[0])), static_cast<std::uint8_t>(std::lround(c[1])),
          static_cast<std::uint8_t>(std::lround(c[2]))};
}

Image render_false_colour(const Solution& s, const std::vector<double>& face_value, const RenderOptions& o,
                          const FalseColourOptions& fc) {
  auto to_t = [&](double v) {
    if (fc.log_scale) {
      const double l = std::log10(std::max(fc.lo, 1e-300)), h = std::log10(std::max(fc.hi, 1e-300));
      return h > l ? (std::log10(std::max(v, 1e-300)) - l) / (h - l) : 0.0;
    }
    return fc.hi > fc.lo ? (v - fc.lo) / (fc.hi - fc.lo) : 0.0;
  };
  Rasterizer r(o.camera);
  // The value rides in the first channel; flat per face.
  fill_faces(r, s, o, [&](std::size_t f, std::size_t) { return Rgb(to_t(face_value[f]), 0.0, 0.0); });
  Image scene = r.finish([](const Rgb& v) { return error_colormap(v[0]); }, o.background);
  if (fc.draw_edges) draw_edges(r, s, o, scene, Rgb8{40, 40, 40});
  if (!fc.legend) return scene;

  const int strip = std::max(64, scene.width / 6);
  Image image(scene.width + strip, scene.height, Rgb8{255, 255, 255});
  for (int y = 0; y < scene.height; ++y)
    for (int x = 0; x < scene.width; ++x) image.at(x, y) = scene.at(x, y);
  const int scale = std::max(1, scene.height / 256);
  const int bar_x0 = scene.width + strip / 8, bar_x1 = bar_x0 + strip / 4;
  const int bar_y0 = scene.height / 10 + 8 * scale, bar_y1 = scene.height - scene.height / 10 - 8 * scale;
  for (int y = bar_y0; y <= bar_y1; ++y) {
    const Rgb8 c = error_colormap(static_cast<double>(bar_y1 - y) / std::max(1, bar_y1 - bar_y0));
    for (int x = bar_x0; x <= bar_x1; ++x) image.at(x, y) = c;
  }
  const Rgb8 ink{0, 0, 0};
  draw_text(image, bar_x0, bar_y0 - 7 * scale, fmt::format("{:.2g}", fc.hi), ink, scale);
  draw_text(image, bar_x0, bar_y1 + 2 * scale, fmt::format("{:.2g}", fc.lo), ink, scale);
  return image;
}

void draw_text(Image& image, int x, int y, const std::string& text, Rgb8 colour, int scale) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const int gx = x + static_cast<int>(i) * 4 * scale;
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col) {
        if (!((glyph_row(text[i], row) >> (2 - col)) & 1)) continue;
        for (int dy = 0; dy < scale; ++dy)
          for (int dx = 0; dx < scale; ++dx) {
            const int px = gx + col * scale + dx, py = y + row * scale + dy;
            if (px >= 0 && py >= 0 && px < image.width && py < image.height) image.at(px, py) = colour;
          }
      }
  }
}

}  // namespace hrad
