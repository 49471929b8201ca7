// hrad render SOLUTION.ply --out IMAGE.png [options]
// hrad render SOLUTION.ply --scene SCENE --final-gather --out IMAGE.png [--exr IMAGE.exr] [options]
//
// Renders a solution written by `hrad solve` (PLY with per-vertex and per-element radiosity) with
// hrad's software rasterizer. Files are written atomically. By default each element's
// vertex-interpolated radiosity is drawn (Gouraud). With --final-gather every pixel's samples
// gather the radiosity where they meet the scene, B(x) = E + rho sum_j F(x -> j) V(x, j) B_j over
// sources j with exact point-to-polygon factors: through the links a hierarchical solve stores in
// its file (lib/hrad/gather/link_gather.h: the sources of the links on the leaf's path, each
// classified from the leaf), else over the solution's leaves (lib/hrad/gather/leaf_gather.h: the
// leaves of a distant patch grouped within --gather-tolerance); partly visible sources sampled by
// rays shared over the point. The picture no longer shows the elements: shadows are resolved at
// the pixels. The time of the image and the work of the gather are printed; progress with
// the time left goes to stderr.
//
//   --out IMAGE.png        output image (required); a name ending in .exr writes an OpenEXR file
//                          of the linear values instead (the mean radiosity over each pixel's
//                          samples, in the scene's exitance units; radiance is that over pi)
//   --exr IMAGE.exr        also write the linear values as OpenEXR, beside the PNG
//   --samples-per-pixel N  jittered samples per pixel, averaged (default 4; 1 samples the centres)
//   --final-gather         gather at every sample instead of interpolating the elements; needs --scene
//   --gather-tolerance T   Barnes-Hut tolerance of the gather, relative to the mean radiosity
//                          (default 1e-2; 0 gathers every leaf on its own; larger is faster on
//                          fine solutions: the leaves of distant patches are grouped)
//   --visibility-samples K rays per gathered point shared by its partly visible leaves (default 32)
//   --gather-sources S     links (the solution's stored links; an error when it has none) or all
//                          (every patch); default: links when the solution has them, else all
//   --threads N            worker threads of the gather (default: all cores); the image is the
//                          same at any count
//   --seed S               seed of the pixels' jitter and the gather's rays (default 1)
//   --quiet                no progress on stderr
//   --camera px,py,pz,tx,ty,tz,ux,uy,uz,fov_deg
//                          camera position, look-at point, up vector and vertical field of view in
//                          degrees; default: the Cornell box camera for a Cornell-box-sized scene,
//                          else a camera fitted to the bounding box
//   --width W --height H   image size in pixels (default 512 x 512)
//   --exposure X           radiosity scale before the sRGB curve (default: the 95th percentile of
//                          the area-weighted element luminance maps to 0.8)
//   --wireframe            flat-shaded elements with their edges (the element mesh)
//   --both-sides           draw back faces too (default: polygons facing away are skipped)
//   --scene SCENE          the scene the solution was solved on (with --final-gather or --reference)
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
#include <cctype>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "comma_numbers.h"
#include "commands.h"
#include "hrad/analysis/error_metrics.h"
#include "hrad/core/error.h"
#include "hrad/core/face_geometry.h"
#include "hrad/core/memory.h"
#include "hrad/core/tone_map.h"
#include "hrad/gather/gathered_image.h"
#include "hrad/gather/leaf_gather.h"
#include "hrad/gather/solution_gather.h"
#include "hrad/io/atomic_file.h"
#include "hrad/io/exr_writer.h"
#include "hrad/io/png_writer.h"
#include "hrad/io/scene_reader.h"
#include "hrad/io/solution_ply.h"
#include "hrad/render/render.h"
#include "seed_option.h"

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

bool ends_with_exr(const std::string& path) {
  if (path.size() < 4) return false;
  std::string tail = path.substr(path.size() - 4);
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return std::tolower(c); });
  return tail == ".exr";
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
    std::string reference, scene, error_range, exr, gather_sources;
    bool log_scale = false, include_emitters = false, final_gather = false, quiet = false;
    int samples_per_pixel = 4, visibility_samples = 32, threads = 0;
    double gather_tolerance = 1e-2;
    std::uint64_t seed = 1;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("SOLUTION", args->solution, "Solution file (.ply) written by hrad solve")->required();
  cmd->add_option("--out", args->out, "Output image: PNG, or OpenEXR (linear values) for a name ending in .exr")
      ->required();
  cmd->add_option("--exr", args->exr, "Also write the linear values as OpenEXR");
  cmd->add_option("--samples-per-pixel", args->samples_per_pixel, "Jittered samples per pixel (default 4)");
  cmd->add_flag("--final-gather", args->final_gather, "Gather the radiosity at every sample (needs --scene)");
  cmd->add_option("--gather-tolerance", args->gather_tolerance,
                  "Barnes-Hut tolerance of the gather, relative to the mean radiosity (default 1e-2)");
  cmd->add_option("--visibility-samples", args->visibility_samples,
                  "Rays per gathered point for its partly visible leaves (default 32)");
  cmd->add_option("--gather-sources", args->gather_sources,
                  "links | all: gather through the solution's links or over every patch (default: links if stored)");
  cmd->add_option("--threads", args->threads, "Worker threads of the gather (default: all cores)");
  cmd->add_option("--seed", args->seed, "Seed of the jitter and the gather's rays (default 1)")
      ->check(cli::seed_validator());
  cmd->add_flag("--quiet", args->quiet, "No progress on stderr");
  cmd->add_option("--camera", args->camera,
                  "px,py,pz,tx,ty,tz,ux,uy,uz,fov_deg: position, look-at, up, vertical field of view (degrees)");
  cmd->add_option("--width", args->width, "Image width in pixels (default 512)");
  cmd->add_option("--height", args->height, "Image height in pixels (default 512)");
  cmd->add_option("--exposure", args->exposure, "Radiosity scale before the sRGB curve (default: automatic)");
  cmd->add_flag("--wireframe", args->wireframe, "Draw the element mesh over flat-shaded elements");
  cmd->add_flag("--both-sides", args->both_sides, "Also draw polygons whose front faces away from the camera");
  cmd->add_option("--reference", args->reference, "Reference solution (.ply): draw the relative error instead");
  cmd->add_option("--scene", args->scene, "Scene of the solution; required with --final-gather and --reference");
  cmd->add_option("--error-range", args->error_range, "LO,HI: colour-bar range of the error image");
  cmd->add_flag("--log", args->log_scale, "Logarithmic colour scale for the error image");
  cmd->add_flag("--include-emitters", args->include_emitters, "Measure the error on emitting patches too");
  cmd->callback([args, cmd] {
    if (args->width < 1 || args->width > 16384)
      throw Error(fmt::format("--width: {} is not in [1, 16384]", args->width));
    if (args->height < 1 || args->height > 16384)
      throw Error(fmt::format("--height: {} is not in [1, 16384]", args->height));
    if (cmd->count("--exposure") && !(args->exposure > 0.0 && std::isfinite(args->exposure)))
      throw Error(fmt::format("--exposure: {} is not a positive number", args->exposure));
    if (args->samples_per_pixel < 1 || args->samples_per_pixel > 1024)
      throw Error(fmt::format("--samples-per-pixel: {} is not in [1, 1024]", args->samples_per_pixel));
    if (args->threads < 0) throw Error(fmt::format("--threads: {} is not >= 0 (0 = all cores)", args->threads));
    // Per pixel: the rasterizer's depth, value and polygon id (36 bytes), the sums that average the
    // samples, the linear image and the display (79 bytes); with --final-gather, per sample its
    // point, pixel and gathered irradiance (88 bytes). Refused up front rather than std::bad_alloc.
    {
      const double per_pixel = 115.0 + (args->final_gather ? 88.0 * args->samples_per_pixel : 0.0);
      const double bytes = per_pixel * args->width * args->height, available = available_memory_bytes();
      if (available > 0.0 && bytes > 0.8 * available)
        throw Error(
            fmt::format("--width/--height: a {} x {} image needs about {} and this process may use {}: "
                        "render smaller",
                        args->width, args->height, format_bytes(bytes), format_bytes(available)));
    }
    LeafGatherOptions gather_options;
    gather_options.tolerance = args->gather_tolerance;
    gather_options.visibility_samples = args->visibility_samples;
    gather_options.partial = PartialSampling::shared;
    gather_options.classify_points = false;
    gather_options.seed = args->seed;
    validate_leaf_gather_options(gather_options);
    const GatherSources sources =
        args->gather_sources.empty() ? GatherSources::automatic : parse_gather_sources(args->gather_sources);
    // Every option is checked before any file is read.
    const bool error_image = !args->reference.empty();
    if (error_image && args->final_gather) throw Error("--final-gather: not with --reference (an error image)");
    if (args->final_gather && args->wireframe) throw Error("--final-gather: not with --wireframe");
    if ((error_image || args->final_gather) && args->scene.empty())
      throw Error(fmt::format("--scene: required with {}", error_image ? "--reference" : "--final-gather"));
    if (!error_image && !args->final_gather && !args->scene.empty())
      throw Error("--scene: only with --final-gather or --reference");
    if (!error_image && (!args->error_range.empty() || args->log_scale || args->include_emitters))
      throw Error("--reference: --error-range, --log and --include-emitters only apply to an error image");
    if (!args->final_gather)
      for (const char* option : {"--gather-tolerance", "--visibility-samples", "--gather-sources", "--threads"})
        if (cmd->count(option)) throw Error(fmt::format("{}: only with --final-gather", option));
    if (!args->exr.empty() && (error_image || args->wireframe))
      throw Error("--exr: the linear values of a Gouraud or gathered image only (not an error image or a wireframe)");
    if (ends_with_exr(args->out) && (error_image || args->wireframe))
      throw Error("--out: an OpenEXR image holds the linear values of a Gouraud or gathered image only");
    std::optional<Camera> camera;
    if (!args->camera.empty()) camera = parse_camera(args->camera, args->width, args->height);
    std::optional<std::pair<double, double>> error_range;
    if (!args->error_range.empty()) error_range = parse_range(args->error_range);
    if (args->log_scale && error_range && !(error_range->first > 0.0))
      throw Error("--error-range: LO must be positive with --log");

    OutputFiles outputs;
    outputs.declare("--out", args->out);
    if (!args->exr.empty()) outputs.declare("--exr", args->exr);
    outputs.check_inputs(
        {{"the solution", args->solution}, {"--reference", args->reference}, {"--scene", args->scene}});
    std::optional<SolutionLinks> stored;
    const Solution solution = read_solution_ply(args->solution, args->final_gather ? &stored : nullptr);
    RenderOptions options;
    options.camera = camera ? *camera : default_camera(solution, args->width, args->height);
    options.exposure = cmd->count("--exposure") ? args->exposure : auto_exposure(solution);
    options.cull_back_faces = !args->both_sides;
    options.samples_per_pixel = args->samples_per_pixel;
    options.seed = args->seed;
    if (!args->quiet) options.progress = [](std::string_view line) { std::cerr << "hrad render: " << line << "\n"; };
    std::optional<Scene> scene;
    if (!args->scene.empty()) {
      ObjReadOptions read_options;
      read_options.cut_near_faces = solution.near_faces_cut;  // the patches the solve had
      scene = read_scene(args->scene, nullptr, read_options);
      std::vector<std::pair<std::string, std::string>> inputs;
      for (const std::string& f : scene->files) inputs.emplace_back("an input of --scene", f);
      outputs.check_inputs(inputs);
      check_solution_patches(solution, args->solution, *scene, args->scene);
    }
    const AllocationScope allocating(
        fmt::format("the {} x {} image at {} samples per pixel", args->width, args->height, args->samples_per_pixel),
        "render smaller (--width, --height, --samples-per-pixel)");
    Image image;
    std::optional<HdrImage> linear;
    if (args->final_gather) {
      std::unique_ptr<tbb::global_control> limit;
      if (args->threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, args->threads);
      const SolutionGather gather(*scene, solution, stored, args->solution, sources, gather_options);
      GatheredImage gathered = render_gathered(solution, gather.gather(), options);
      image = std::move(gathered.display);
      linear = std::move(gathered.radiosity);
      const GatherWork& w = gathered.work;
      const double per_point = w.points ? 1.0 / static_cast<double>(w.points) : 0.0;
      std::cout << fmt::format(
          "final gather: {}x{} pixels, {} samples per pixel, {} points in {:.2f} s ({:.2f} s gathering {}, {:.3g} "
          "points/s); per point: {:.1f} point factors, {:.1f} leaves covered, {:.1f} shaft tests, {:.1f} rays\n",
          image.width, image.height, args->samples_per_pixel, gathered.points, gathered.seconds,
          gathered.gather_seconds, gather.description(),
          gathered.gather_seconds > 0.0 ? gathered.points / gathered.gather_seconds : 0.0, per_point * w.node_visits,
          per_point * w.leaves_covered, per_point * w.classifications, per_point * w.rays);
    } else if (error_image) {
      const Solution reference = read_solution_ply(args->reference);
      check_solution_patches(reference, args->reference, *scene, args->scene);
      const ErrorMetrics metrics = compare_solutions(*scene, solution, reference, 256,
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
    } else if (args->wireframe) {
      image = render_wireframe(solution, options);
    } else {
      RenderedImage gouraud = render_solution_with_linear(solution, options);
      image = std::move(gouraud.display);
      linear = std::move(gouraud.linear);
    }
    if (ends_with_exr(args->out))
      write_exr(args->out, *linear);
    else
      write_png(args->out, image);
    if (!args->exr.empty()) write_exr(args->exr, *linear);
    outputs.commit();
    std::cout << fmt::format("{}: {}x{} image of {} elements, exposure {:.6g}\n", args->out, image.width, image.height,
                             solution.faces.size(), options.exposure);
  });
}

}  // namespace hrad::cli
