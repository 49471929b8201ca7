// Images of a Solution: Gouraud-shaded radiosity, the element mesh over flat shading (with
// optional links), and a false-colour map of a per-element value (e.g. relative error).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "hrad/core/image.h"
#include "hrad/core/progress.h"
#include "hrad/core/solution.h"
#include "hrad/render/camera.h"

namespace hrad {

struct RenderOptions {
  Camera camera;
  double exposure = 1.0;        ///< see tone_map()
  bool cull_back_faces = true;  ///< skip polygons whose front (CCW) side faces away from the camera
  Rgb8 background{0, 0, 0};
  /// Jittered samples per pixel (pixel_samples.h), averaged by PixelAverager; 1 samples the centres.
  int samples_per_pixel = 1;
  std::uint64_t seed = 1;  ///< of the jitter
  /// Progress lines for large meshes (core/progress.h: at most one every 2 s; none for quick renders).
  ProgressSink progress;
};

/// Axis-aligned bounds (lo, hi) of the solution's vertices.
std::pair<Vec3, Vec3> solution_bounds(const Solution& solution);

/// The Cornell box camera when the solution's bounds are those of the Cornell box (within
/// [-1, 560]^3 and wider than 500 along each axis), else fit_camera() on its bounds.
Camera default_camera(const Solution& solution, int width, int height);

/// Averages a few samples per pixel into a display image and a linear one. Display: each covered
/// sample's clamp(exposure * value, 0, 1) and, for each sample that saw nothing, the background
/// (sRGB-decoded), averaged in linear light and sRGB-encoded (so an edge against a bright light is
/// antialiased as it looks; with one sample a pixel is tone_map() of its value or the background).
/// Linear: the mean value over the pixel's samples, 0 where a sample saw nothing.
class PixelAverager {
 public:
  PixelAverager(int width, int height, int samples_per_pixel, double exposure, Rgb8 background);
  /// One covered sample of pixel (x, y); samples of a pixel must come in the same order every run
  /// for the same bits (sums are not associative).
  void add(int x, int y, const Rgb& value);
  Image display() const;
  HdrImage linear() const;

 private:
  int width_, height_, samples_;
  double exposure_;
  Rgb8 background_;
  std::vector<Rgb> value_sum_, display_sum_;
  std::vector<int> covered_;
};

/// Gouraud shading of Solution::vertex_radiosity (perspective-correct), tone-mapped, with
/// options.samples_per_pixel jittered samples per pixel (PixelAverager).
Image render_solution(const Solution& solution, const RenderOptions& options);

struct RenderedImage {
  Image display;
  HdrImage linear;  ///< the interpolated radiosity averaged over each pixel's samples
};
/// render_solution() with its linear values (for HDR files).
RenderedImage render_solution_with_linear(const Solution& solution, const RenderOptions& options);

/// Whether face `f`'s front (counter-clockwise side) faces the camera's position.
bool faces_camera(const Solution& solution, std::size_t f, const Camera& camera);

struct WireframeOptions {
  Rgb8 edge_colour{20, 20, 20};
  Rgb8 link_colour{255, 170, 0};
  /// Segments drawn after the mesh, e.g. links between element centroids (depth-tested).
  std::vector<std::pair<Vec3, Vec3>> links;
};

/// Each element flat-shaded with its constant Solution::face_radiosity, its edges drawn on top.
Image render_wireframe(const Solution& solution, const RenderOptions& options, const WireframeOptions& wireframe = {});

/// Blue (t = 0) through white (t = 0.5) to red (t = 1), linear between the three in sRGB; t clamped
/// (+infinity is red); NaN ("not measured") is mid grey.
Rgb8 error_colormap(double t);

struct FalseColourOptions {
  double lo = 0.0;          ///< value drawn blue
  double hi = 1.0;          ///< value drawn red
  bool log_scale = false;   ///< colour by log10(value) between log10(lo) and log10(hi)
  bool legend = true;       ///< add a colour bar with the lo and hi labels on the right
  bool draw_edges = false;  ///< outline the elements
};

/// Each element flat-coloured by error_colormap of its `face_value` (one per Solution face).
/// With a legend the image is wider than the camera's by a strip of max(64, width / 6) pixels.
Image render_false_colour(const Solution& solution, const std::vector<double>& face_value, const RenderOptions& options,
                          const FalseColourOptions& colours);

/// Draws `text` (digits, '.', '-', '+', 'e', 'E', '%', 'l', 'x', ' ') with a 3x5 pixel font scaled by
/// `scale`, top-left at (x, y), clipped to the image.
void draw_text(Image& image, int x, int y, const std::string& text, Rgb8 colour, int scale = 2);

}  // namespace hrad
