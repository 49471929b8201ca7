// hrad render SOLUTION.ply --out IMAGE.png [options]
//
// Renders a solution written by `hrad solve` (PLY with per-vertex and per-element radiosity) to a
// PNG with hrad's software rasterizer. The file is written atomically.
//
//   --out IMAGE.png        output image (required)
//   --camera px,py,pz,tx,ty,tz,ux,uy,uz,fov_deg
//                          camera position, look-at point, up vector and vertical field of view in
//                          degrees; default: the Cornell box camera for a Cornell-box-sized scene,
//                          else a camera fitted to the bounding box
//   --width W --height H   image size in pixels (default 512 x 512)
//   --exposure X           radiosity scale before the sRGB curve (default: the 95th percentile of
//                          the area-weighted element luminance maps to 0.8)
//   --wireframe            flat-shaded elements with their edges (the element mesh)
//   --both-sides           draw back faces too (default: polygons facing away are skipped)
//   --reference REF.ply --scene SCENE.obj
//                          false-colour image of each element's relative L2 error against the
//                          reference solution (analysis/error_metrics.h: samples per patch of the
//                          scene), with a colour bar; prints the overall relative L2 and Linf errors
//   --error-range LO,HI    colour-bar range for the error image (default 0 to the area-weighted 95th
//                          percentile of the element errors; larger errors are drawn red)
//   --log                  logarithmic colour scale for the error image
//   --include-emitters     measure emitting patches too (default: left out, drawn grey, since
//                          their given emission dominates the norms)
#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "comma_numbers.h"
#include "commands.h"
#include "hrad/core/error.h"
#include "hrad/core/memory.h"
#include "hrad/analysis/error_metrics.h"
#include "hrad/io/atomic_file.h"
#include "hrad/io/scene_reader.h"
#include "hrad/io/png_writer.h"
#include "hrad/io/solution_ply.h"
#include "hrad/render/face_geometry.h"
#include "hrad/render/render.h"
#include "hrad/render/tone_map.h"

namespace hrad::cli {
namespace {

Camera parse_camera(const std::string& text, int width, int height) {
  const std::string usage = "--camera: expected 10 comma-separated numbers px,py,pz,tx,ty,tz,ux,uy,uz,fov_deg";
  const std::optional<std::vector<double>> numbers = comma_numbers(text);
  if (!numbers) throw Error(fmt::format("{}, got '{}'", usage, text));
  const std::vector<double>& v = *numbers;
  if (v.size() != 10) throw Error(fmt::format("{}, got {} in '{}'", usage, v.size(), text));
  Camera c;
  c.position = Vec3(v[0], v[1], v[2]);
  c.target = Vec3(v[3], v[4], v[5]);
  c.up = Vec3(v[6], v[7], v[8]);
  c.vfov_deg = v[9];
  c.width = width;
  c.height = height;
  const Vec3 forward = c.target - c.position;
  if (forward.norm() == 0.0) throw Error("--camera: the look-at point equals the position");
  if (forward.normalized().cross(c.up).norm() < 1e-9 * std::max(1.0, c.up.norm()))
    throw Error("--camera: the up vector is zero or parallel to the viewing direction");
  if (!(c.vfov_deg > 0.0 && c.vfov_deg < 180.0))
    throw Error(fmt::format("--camera: field of view {} is not in (0, 180) degrees", c.vfov_deg));
  return c;
}

std::pair<double, double> parse_range(const std::string& text) {
  const std::string usage = "--error-range: expected LO,HI with 0 <= LO < HI";
  const std::optional<std::vector<double>> v = comma_numbers(text);
  if (!v || v->size() != 2) throw Error(fmt::format("{}, got '{}'", usage, text));
  const double lo = (*v)[0], hi = (*v)[1];
  if (!(lo >= 0.0 && hi > lo)) throw Error(fmt::format("{}, got '{}'", usage, text));
  return {lo, hi};
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render a solution PLY to a PNG image (software rasterizer)");
  struct Args {
    std::string solution, out, camera;
    int width = 512, height = 512;
    double exposure = 0.0;
    bool wireframe = false, both_sides = false;
    std::string reference, scene, error_range;
    bool log_scale = false, include_emitters = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("SOLUTION", args->solution, "Solution file (.ply) written by hrad solve")->required();
  cmd->add_option("--out", args->out, "Output PNG image")->required();
  cmd->add_option("--camera", args->camera,
                  "px,py,pz,tx,ty,tz,ux,uy,uz,fov_deg: position, look-at, up, vertical field of view (degrees)");
  cmd->add_option("--width", args->width, "Image width in pixels (default 512)");
  cmd->add_option("--height", args->height, "Image height in pixels (default 512)");
  cmd->add_option("--exposure", args->exposure, "Radiosity scale before the sRGB curve (default: automatic)");
  cmd->add_flag("--wireframe", args->wireframe, "Draw the element mesh over flat-shaded elements");
  cmd->add_flag("--both-sides", args->both_sides, "Also draw polygons whose front faces away from the camera");
  cmd->add_option("--reference", args->reference, "Reference solution (.ply): draw the relative error instead");
  cmd->add_option("--scene", args->scene, "Scene (.obj) of both solutions; required with --reference");
  cmd->add_option("--error-range", args->error_range, "LO,HI: colour-bar range of the error image");
  cmd->add_flag("--log", args->log_scale, "Logarithmic colour scale for the error image");
  cmd->add_flag("--include-emitters", args->include_emitters, "Measure the error on emitting patches too");
  cmd->callback([args, cmd] {
    if (args->width < 1 || args->width > 16384)
      throw Error(fmt::format("--width: {} is not in [1, 16384]", args->width));
    if (args->height < 1 || args->height > 16384)
      throw Error(fmt::format("--height: {} is not in [1, 16384]", args->height));
    // Per pixel: the RGB image, the depth buffer (double) and the per-pixel face ids and weights the
    // error image keeps: 32 bytes is an upper bound. Refused up front rather than std::bad_alloc.
    {
      const double bytes = 32.0 * args->width * args->height, available = available_memory_bytes();
      if (available > 0.0 && bytes > 0.8 * available)
        throw Error(fmt::format("--width/--height: a {} x {} image needs about {} and this process may use {}: "
                                "render smaller",
                                args->width, args->height, format_bytes(bytes), format_bytes(available)));
    }
    if (cmd->count("--exposure") && !(args->exposure > 0.0 && std::isfinite(args->exposure)))
      throw Error(fmt::format("--exposure: {} is not a positive number", args->exposure));
    // Every option is checked before any file is read.
    if (!args->reference.empty() && args->scene.empty()) throw Error("--scene: required with --reference");
    if (args->reference.empty() &&
        (!args->scene.empty() || !args->error_range.empty() || args->log_scale || args->include_emitters))
      throw Error("--reference: --scene, --error-range, --log and --include-emitters only apply to an error image");
    std::optional<Camera> camera;
    if (!args->camera.empty()) camera = parse_camera(args->camera, args->width, args->height);
    std::optional<std::pair<double, double>> error_range;
    if (!args->error_range.empty()) error_range = parse_range(args->error_range);
    if (args->log_scale && error_range && !(error_range->first > 0.0))
      throw Error("--error-range: LO must be positive with --log");

    OutputFiles outputs;
    outputs.declare("--out", args->out);
    outputs.check_inputs({{"the solution", args->solution}, {"--reference", args->reference}, {"--scene", args->scene}});
    const Solution solution = read_solution_ply(args->solution);
    RenderOptions options;
    options.camera = camera ? *camera : default_camera(solution, args->width, args->height);
    options.exposure = cmd->count("--exposure") ? args->exposure : auto_exposure(solution);
    options.cull_back_faces = !args->both_sides;
    options.progress = [](std::string_view line) { std::cerr << "hrad render: " << line << "\n"; };
    Image image;
    if (!args->reference.empty()) {
      const Scene scene = read_scene(args->scene);
      std::vector<std::pair<std::string, std::string>> inputs;
      for (const std::string& f : scene.files) inputs.emplace_back("an input of --scene", f);
      outputs.check_inputs(inputs);
      const Solution reference = read_solution_ply(args->reference);
      for (int p : solution.face_patch)
        if (static_cast<std::size_t>(p) >= scene.patches.size())
          throw Error(fmt::format("{}: patch id {} but {} has {} patches", args->solution, p, args->scene,
                                  scene.patches.size()));
      for (int p : reference.face_patch)
        if (static_cast<std::size_t>(p) >= scene.patches.size())
          throw Error(fmt::format("{}: patch id {} but {} has {} patches", args->reference, p, args->scene,
                                  scene.patches.size()));
      const ErrorMetrics metrics = compare_solutions(scene, solution, reference, 256,
                                                     args->include_emitters ? Emitters::include : Emitters::exclude);
      FalseColourOptions colours;
      colours.log_scale = args->log_scale;
      if (error_range) {
        std::tie(colours.lo, colours.hi) = *error_range;
      } else {
        // The 95th percentile by area: a few elements where the reference is nearly black (under
        // the Cornell blocks, say) have huge relative errors and would wash out the rest.
        std::vector<std::pair<double, double>> by_error;  // (error, area)
        double total = 0.0;
        for (std::size_t f = 0; f < solution.faces.size(); ++f) {
          const double e = metrics.face_relative_l2[f];
          if (!std::isfinite(e)) continue;
          by_error.emplace_back(e, face_area(solution, f));
          total += by_error.back().second;
        }
        std::sort(by_error.begin(), by_error.end());
        double acc = 0.0;
        colours.hi = 0.0;
        for (const auto& [e, a] : by_error) {
          acc += a;
          colours.hi = e;
          if (acc >= 0.95 * total) break;
        }
        colours.lo = args->log_scale ? colours.hi * 1e-3 : 0.0;
        if (colours.hi == 0.0) colours.hi = 1.0;
      }
      if (colours.log_scale && !(colours.lo > 0.0)) throw Error("--error-range: LO must be positive with --log");
      image = render_false_colour(solution, metrics.face_relative_l2, options, colours);
      std::cout << fmt::format(
          "relative L2 error {:.6g}, relative Linf error {:.6g} ({} samples{}); colour range {:.3g} to {:.3g}\n",
          metrics.relative_l2, metrics.relative_linf, metrics.samples,
          args->include_emitters ? "" : ", emitters left out", colours.lo, colours.hi);
    } else {
      image = args->wireframe ? render_wireframe(solution, options) : render_solution(solution, options);
    }
    write_png(args->out, image);
    outputs.commit();
    std::cout << fmt::format("{}: {}x{} image of {} elements, exposure {:.6g}\n", args->out, image.width, image.height,
                             solution.faces.size(), options.exposure);
  });
}

}  // namespace hrad::cli
