// hrad probe SOLUTION.ply --scene SCENE --points P.csv --out R.csv [options]
// hrad probe SOLUTION.ply --scene SCENE --grid AXIS,HEIGHT,U0,V0,U1,V1,NU,NV --out R.csv [options]
//
// Light at points from a solution written by `hrad solve`, by final gather (lib/hrad/gather/probes.h):
// the irradiance H(x) = sum_j F(x -> j) V(x, j) B_j a sensor at x facing n receives from the
// solution's sources j, with Lambert's exact point-to-polygon factor and visibility decided from the
// point itself (the sources of the links on the point's leaf's path when the solution stores a
// hierarchical solve's links, lib/hrad/gather/link_gather.h; else, and for points in space, every
// patch's leaves, lib/hrad/gather/leaf_gather.h), in the scene's exitance units (lux when the emission is luminous
// exitance in lm/m^2). A point on a patch's front (within 1e-6 of the scene's size, its normal within ~1.4 mrad of the
// patch's) also gets that patch's radiosity B = E + rho H; the points need not lie on a surface. The same points
// answered by `hrad reference` (Monte Carlo, independent) give the same columns, with standard errors.
//
//   --scene SCENE          the scene the solution was solved on (required)
//   --points P.csv         probe points, one a row under the header x,y,z,nx,ny,nz (position and the
//                          direction the sensor faces)
//   --grid AXIS,HEIGHT,U0,V0,U1,V1,NU,NV
//                          instead of --points: a work plane, the centres of NU x NV cells over the
//                          rectangle (U0, V0)-(U1, V1) in the plane AXIS = HEIGHT, facing +AXIS
//                          (AXIS is x, y, z, or -x, -y, -z to face the other way); U and V are the
//                          two other coordinates in their order (y: x, z). E.g. a desk plane 0.75
//                          above a floor y = 0: --grid y,0.75,0,0,4,3,40,30
//   --out R.csv            the results, written atomically: x,y,z,nx,ny,nz (as given; the normal as a
//                          unit vector), face (the input face the point lies on, empty in space),
//                          irradiance_r,irradiance_g,irradiance_b, radiosity_r,radiosity_g,radiosity_b
//                          (empty in space); grid points in the order u fastest, then v
//   --gather-tolerance T   Barnes-Hut tolerance of the gather, relative to the mean radiosity
//                          (default 1e-3; 0 gathers every leaf on its own; see leaf_gather.h)
//   --visibility-samples K points per partly visible leaf, kernel-weighted (default 64)
//   --exact-visibility     the exact visible region of each partly visible leaf instead of samples
//                          (CGAL; milliseconds a leaf: the reference for the sampled estimate); over
//                          all patches
//   --gather-sources S     links (the solution's stored links; an error when it has none) or all
//                          (every patch); default: links when the solution has them (and no
//                          --exact-visibility), else all
//   --threads N            worker threads (default: all cores); the values do not depend on it
//   --seed S               seed of the visibility samples (default 1)
//   --emission-units U     the unit of the scene's emission (MTL Ke): lm/m2 (luminous exitance) or
//                          W/m2 (radiant exitance of white light); the results then gain a column
//                          illuminance_lux (lib/hrad/gather/photometry.h: Radiance's luminance
//                          weights, and 179 lm/W for W/m2). Default: the unit the scene file declares
//                          ("#@hrad emission-units lm/m2", README "Scene format"); the option overrides
//                          a declaration, with a warning when they differ
//   --isolux IMAGE.png     with --grid: a false-colour isolux plot of the grid as seen from the side
//                          its points face (u to the right; v up, or down where u x v points the
//                          other way, as for y; lib/hrad/render/isolux_image.h), bands between
//                          round levels, isolines and
//                          a labelled colour bar; in lux with a unit (declared or the option), otherwise the
//                          luminance-weighted irradiance in the scene's units
//   --quiet                no progress on stderr
// A summary (points, seconds, work per point; with --grid the least, mean and greatest value and
// the uniformity least / mean) goes to stdout. Bad options and files are a one-line
// error naming the option or file:line, before any work; nothing is written then.
#include <algorithm>
#include <cctype>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <tbb/global_control.h>

#include "comma_numbers.h"
#include "commands.h"
#include "csv_cells.h"
#include "hrad/core/error.h"
#include "hrad/core/stopwatch.h"
#include "hrad/gather/leaf_gather.h"
#include "hrad/gather/photometry.h"
#include "hrad/gather/probes.h"
#include "hrad/gather/solution_gather.h"
#include "hrad/io/atomic_file.h"
#include "hrad/io/png_writer.h"
#include "hrad/io/points_csv.h"
#include "hrad/io/scene_reader.h"
#include "hrad/io/solution_ply.h"
#include "hrad/render/isolux_image.h"
#include "seed_option.h"

namespace hrad::cli {
namespace {

ProbeGrid parse_grid(const std::string& text) {
  const std::string usage = "--grid: expected AXIS,HEIGHT,U0,V0,U1,V1,NU,NV with AXIS one of x, y, z, -x, -y, -z";
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos) throw Error(fmt::format("{}, got '{}'", usage, text));
  std::string axis = text.substr(0, comma);
  ProbeGrid g;
  g.facing_positive = true;
  if (!axis.empty() && (axis[0] == '-' || axis[0] == '+')) {
    g.facing_positive = axis[0] == '+';
    axis = axis.substr(1);
  }
  if (axis.size() != 1 || std::string("xyzXYZ").find(axis[0]) == std::string::npos)
    throw Error(fmt::format("{}, got axis '{}'", usage, text.substr(0, comma)));
  g.axis = std::tolower(static_cast<unsigned char>(axis[0])) - 'x';
  const std::optional<std::vector<double>> numbers = comma_numbers(text.substr(comma + 1));
  if (!numbers || numbers->size() != 7) throw Error(fmt::format("{}, got '{}'", usage, text));
  const std::vector<double>& v = *numbers;
  g.height = v[0];
  g.u0 = v[1];
  g.v0 = v[2];
  g.u1 = v[3];
  g.v1 = v[4];
  if (!(g.u1 > g.u0 && g.v1 > g.v0))
    throw Error(fmt::format("--grid: the rectangle ({}, {})-({}, {}) is empty (need U0 < U1 and V0 < V1)", g.u0, g.v0,
                            g.u1, g.v1));
  for (int k : {5, 6})
    if (!(v[k] >= 1.0 && v[k] <= 100000.0 && v[k] == static_cast<double>(static_cast<long>(v[k]))))
      throw Error(fmt::format("--grid: {} {} is not a whole number in [1, 100000]", k == 5 ? "NU" : "NV", v[k]));
  g.nu = static_cast<int>(v[5]);
  g.nv = static_cast<int>(v[6]);
  if (static_cast<double>(g.nu) * g.nv > 1e7)
    throw Error(fmt::format("--grid: {} x {} points is more than 10,000,000", g.nu, g.nv));
  return g;
}

}  // namespace

void add_probe_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("probe", "Irradiance (and radiosity on surfaces) at points by final gather");
  struct Args {
    std::string solution, scene, points, grid, out, emission_units, isolux, gather_sources;
    double gather_tolerance = 1e-3;
    int visibility_samples = 64, threads = 0;
    bool exact_visibility = false, quiet = false;
    std::uint64_t seed = 1;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("SOLUTION", args->solution, "Solution file (.ply) written by hrad solve")->required();
  cmd->add_option("--scene", args->scene, "The scene the solution was solved on")->required();
  cmd->add_option("--points", args->points, "Probe points (CSV with header x,y,z,nx,ny,nz)");
  cmd->add_option("--grid", args->grid, "AXIS,HEIGHT,U0,V0,U1,V1,NU,NV: a grid of points on a work plane");
  cmd->add_option("--out", args->out, "Write the results (CSV) here")->required();
  cmd->add_option("--gather-tolerance", args->gather_tolerance,
                  "Barnes-Hut tolerance of the gather, relative to the mean radiosity (default 1e-3)");
  cmd->add_option("--visibility-samples", args->visibility_samples, "Points per partly visible leaf (default 64)");
  cmd->add_flag("--exact-visibility", args->exact_visibility,
                "Exact visible regions instead of samples (over all patches)");
  cmd->add_option("--gather-sources", args->gather_sources,
                  "links | all: gather through the solution's links or over every patch (default: links if stored)");
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)");
  cmd->add_option("--seed", args->seed, "Seed of the visibility samples (default 1)")->check(cli::seed_validator());
  cmd->add_option(
      "--emission-units", args->emission_units,
      "Unit of the scene's emission: lm/m2 or W/m2 (adds illuminance_lux; default: the scene's declaration)");
  cmd->add_option("--isolux", args->isolux, "With --grid: write a false-colour isolux plot (PNG) of the grid");
  cmd->add_flag("--quiet", args->quiet, "No progress on stderr");
  cmd->callback([args, cmd] {
    if (args->points.empty() == args->grid.empty())
      throw Error(args->points.empty() ? "--points: give --points P.csv or --grid" : "--grid: not with --points");
    if (args->threads < 0) throw Error(fmt::format("--threads: {} is not >= 0 (0 = all cores)", args->threads));
    if (args->exact_visibility && cmd->count("--visibility-samples"))
      throw Error("--visibility-samples: not with --exact-visibility");
    LeafGatherOptions options;
    options.tolerance = args->gather_tolerance;
    options.visibility_samples = args->visibility_samples;
    options.visibility = args->exact_visibility ? VisibilityMode::exact : VisibilityMode::sampled;
    options.seed = args->seed;
    validate_leaf_gather_options(options);
    const GatherSources sources =
        args->gather_sources.empty() ? GatherSources::automatic : parse_gather_sources(args->gather_sources);
    if (args->exact_visibility && sources == GatherSources::links)
      throw Error("--gather-sources links: not with --exact-visibility");
    std::optional<ProbeGrid> grid;
    if (!args->grid.empty()) grid = parse_grid(args->grid);
    std::optional<EmissionUnits> units;
    if (cmd->count("--emission-units")) {
      units = parse_emission_units(args->emission_units);
      if (!units) throw Error(fmt::format("--emission-units: '{}' is not lm/m2 or W/m2", args->emission_units));
    }
    if (!args->isolux.empty() && !grid) throw Error("--isolux: needs --grid (a plot of a work plane)");

    OutputFiles outputs;
    outputs.declare("--out", args->out);
    if (!args->isolux.empty()) outputs.declare("--isolux", args->isolux);
    outputs.check_inputs({{"the solution", args->solution}, {"--scene", args->scene}});
    if (!args->points.empty()) outputs.check_inputs({{"--points", args->points}});
    // The probe file first: its defects are the user's most likely ones, and it is cheap to read.
    const std::vector<ProbePoint> points = grid ? grid_points(*grid) : read_points_csv(args->points);
    std::optional<SolutionLinks> stored;
    const Solution solution = read_solution_ply(args->solution, &stored);
    std::vector<std::string> warnings;
    ObjReadOptions read_options;
    read_options.cut_near_faces = solution.near_faces_cut;  // the patches the solve had
    const Scene scene = read_scene(args->scene, &warnings, read_options);
    {
      std::vector<std::pair<std::string, std::string>> inputs;
      for (const std::string& f : scene.files) inputs.emplace_back("an input of --scene", f);
      outputs.check_inputs(inputs);
    }
    check_solution_patches(solution, args->solution, scene, args->scene);
    // The unit: the option's, else the scene's declaration ("#@hrad emission-units lm/m2").
    if (scene.emission_units) {
      if (!units)
        units = scene.emission_units->units;
      else if (*units != scene.emission_units->units)
        warnings.push_back(fmt::format("hrad probe: warning: --emission-units {} overrides {} declared at {}",
                                       to_string(*units), to_string(scene.emission_units->units),
                                       scene.emission_units->where));
    }
    for (const std::string& w : warnings) std::cerr << w << "\n";

    std::unique_ptr<tbb::global_control> limit;
    if (args->threads > 0)
      limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, args->threads);
    const Stopwatch clock;
    const SolutionGather gathering(scene, solution, stored, args->solution, sources, options);
    const FinalGather& gather = gathering.gather();
    ProgressSink sink;
    if (!args->quiet) sink = [](std::string_view line) { std::cerr << "hrad probe: " << line << "\n"; };
    ProgressReporter progress("final gather", points.size(), "points", sink);
    const std::vector<ProbeValue> values = gather_probes(gather, points, &progress);
    progress.finish();
    const double seconds = clock.seconds();

    // Illuminance in lux when the units are declared, else the luminance-weighted irradiance.
    std::vector<double> lux(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      lux[i] = units ? illuminance_lux(values[i].irradiance, *units) : luminance_weighted(values[i].irradiance);
    write_file_atomically(args->out, [&](std::ostream& o) {
      o << "x,y,z,nx,ny,nz,face,irradiance_r,irradiance_g,irradiance_b,radiosity_r,radiosity_g,radiosity_b"
        << (units ? ",illuminance_lux\n" : "\n");
      for (std::size_t i = 0; i < points.size(); ++i) {
        const ProbePoint& p = points[i];
        const ProbeValue& v = values[i];
        const Vec3 n = p.normal.normalized();
        o << fmt::format("{},{},{},{},{},{},", p.position.x(), p.position.y(), p.position.z(), n.x(), n.y(), n.z());
        o << (v.patch >= 0 ? std::to_string(scene.patches[static_cast<std::size_t>(v.patch)].face) : std::string());
        o << "," << rgb_cells(v.irradiance) << ",";
        o << (v.patch >= 0 ? rgb_cells(v.radiosity) : std::string(",,"));
        if (units) o << fmt::format(",{}", lux[i]);
        o << "\n";
      }
    });
    if (!args->isolux.empty()) {
      IsoluxOptions io;
      io.aspect = (grid->u1 - grid->u0) / (grid->v1 - grid->v0);
      io.unit = units ? "lx" : "";
      // Seen from the side the sensors face: v up when u x v points that way (x, y for z; y, z for x).
      io.v_down = (grid->axis == 1) == grid->facing_positive;
      const IsoluxImage plot = render_isolux(lux, grid->nu, grid->nv, io);
      write_png(args->isolux, plot.image);
    }
    outputs.commit();
    const GatherWork w = gather.work();
    const double per_point = w.points ? 1.0 / static_cast<double>(w.points) : 0.0;
    std::cout << fmt::format(
        "{}: {} points in {:.3f} s, gathered {}; per point: {:.1f} point factors, {:.1f} leaves covered, {:.1f} "
        "visibility classifications, {:.1f} rays, {:.2f} exact regions\n",
        args->out, points.size(), seconds, gathering.description(), per_point * w.node_visits,
        per_point * w.leaves_covered, per_point * w.classifications, per_point * w.rays, per_point * w.exact_regions);
    if (grid && !lux.empty()) {
      double lo = lux[0], hi = lux[0], sum = 0.0;
      for (double v : lux) lo = std::min(lo, v), hi = std::max(hi, v), sum += v;
      const double mean = sum / static_cast<double>(lux.size());
      std::cout << fmt::format("{}: least {:.6g}, mean {:.6g}, greatest {:.6g}, uniformity least/mean {:.3f}\n",
                               units ? "illuminance (lux)" : "luminance-weighted irradiance", lo, mean, hi,
                               mean > 0 ? lo / mean : 0.0);
    }
  });
}

}  // namespace hrad::cli
