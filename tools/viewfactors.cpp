// hrad viewfactors SCENE --out F.csv [--report R.json] [options]
//
// The obstructed view-factor matrix F(i -> j) between the input faces of a scene (file order), or
// between its groups with --by group (area-weighted: A_I F_IJ = sum of A_i F_ij over their faces),
// for radiant-exchange codes (lib/hrad/viewfactors/). Every pair of patches is computed once and
// gives both directions, so A_i F_ij = A_j F_ji to rounding; 0 <= F_ij <= its unobstructed value.
//   fully visible pairs (exact shaft classification)  the closed form (Schroeder & Hanrahan 1993)
//   fully hidden pairs                                0
//   partly visible pairs                              the closed form times a kernel-weighted
//                                                     visible fraction, sampled until its standard
//                                                     error is below --visibility-error (the
//                                                     report gives each row's sampling error), or
//                                                     with --exact, the exact visible region at
//                                                     Gauss points (milliseconds per point)
// SCENE may be View3D input (.vs3, lib/hrad/viewfactors/vs3_file.h): its S and M surfaces are the
// rows (combined by their cmb field), O surfaces only obstruct, N surfaces are holes, and
// emissivities come from its emit fields; encl=1 implies --enforce-closure.
// Rows of a closed enclosure whose pairs are all classified exactly sum to 1 within ~1e-10; in an
// open model 1 - (row sum) is the face's factor to the sky.
//
//   --out F            the matrix, format by extension unless --format says:
//                        .csv  dense: one line per face, F to every face, 17 significant digits
//                        .mtx  Matrix Market coordinate (1-based), nonzeros only
//                        .txt  View3D's text layout: header, areas, rows of F, emissivities
//   --format NAME      dense | triplets (CSV "i,j,F", 0-based, nonzeros) | mtx | view3d
//   --by face|group    rows and columns: input faces (default) or groups (`o`/`g` names)
//   --report R.json    areas, row sums, sky, sampling errors, skipped bounds, the largest
//                      reciprocity and closure errors, the work done
//   --visibility-error E   target standard error of a partly visible pair's visible fraction
//                      (default 0.01); rays grow fourfold from 64 up to --max-rays (default 4096)
//   --row-error S      instead of --visibility-error: the target standard error of each row sum's
//                      sampled part; rays are given to partly visible pairs after classification,
//                      in proportion to their unoccluded factors and their rows' partly visible
//                      sums (fewest rays where a pair matters least; for large models)
//   --exact            partly visible pairs by the exact visible region (slow; no sampling error)
//   --threshold T      drop pairs whose unobstructed factor is below T in both directions, found
//                      by a cheap bound from distance and heights or else by the closed form,
//                      before any shaft test (default 0: none); each row reports the sum of
//                      those bounds, the most factor the dropped pairs could hold
//   --sample-below F   pairs whose unobstructed factor is below F both ways (and not dropped)
//                      skip the shaft test: their visible fraction is sampled with --far-rays
//                      point pairs (default 16) against the whole scene (default 0: none; for
//                      large open models, where most pairs are far and their shafts cross
//                      many occluders)
//   --enforce-closure  for closed models: the least-squares adjustment of A_i F_ij that keeps it
//                      symmetric and makes every row sum to 1 (Lawson & Hanson; van Leersum 1989);
//                      the report says how much it moved
//   --write-vs3 M.vs3  also write the scene as View3D input (one S record per patch, the patches
//                      of a face combined into its first; emissivity 1 - reflectance); --out may
//                      then be left out
//   --points P.csv     instead of the matrix, the factor from each probe point (CSV header
//                      x,y,z,nx,ny,nz: position and the normal it faces) to every surface, exact
//                      (Lambert's formula to the exact visible part of each patch): --out gets one
//                      dense CSV line per point (mean radiant temperature, sensors)
//   --boundary B.csv   radiant exchange: header surface,temperature,heat_flux, one row per surface
//                      (0-based), either its temperature (K) or its net flux (W/m^2 leaving); gray
//                      diffuse, emissivity 1 - reflectance (or the .vs3 emit). Solved on the matrix by
//                      the net radiation method (Hottel & Sarofim); needs --heat
//   --heat Q.csv       the exchange's result: surface,name,area,emissivity,temperature,heat_flux
//                      (net W/m^2 leaving),heat_rate (W),radiosity
//   --sky-temperature K    the sky's temperature for the rows' remainder (default 0 K)
//   --method M         how --boundary's exchange is solved: matrix (default: the net radiation
//                      method on the surfaces' view-factor matrix, one radiosity per surface), or
//                      by a radiosity solver on its own elements (lib/hrad/viewfactors/radiosity_exchange.h):
//                      full (the n x n element matrix, LU), substructure (patches shoot, elements
//                      receive) or hierarchical (HSA links, push-pull). The solvers let the radiosity
//                      vary over a surface, write no matrix (no --out, --report or matrix options) and
//                      take the sky at 0 K (they hold no per-element sky factor); unoccluded factors
//                      by the closed form (the solvers' analytic kernel)
//   --max-area A       full, substructure: largest element area (default total area / 250)
//   --patch-area A     substructure: largest shooting-patch area (default total area / 64)
//   --feps F, --aeps A hierarchical: form-factor tolerance (default 0.01), smallest element area
//                      (default total area / 1000)
//   --tolerance T      substructure, hierarchical: iterations stop at this estimated relative error
//                      (default 1e-9)
//   --visibility-samples K  full, substructure, hierarchical: point pairs per partly visible pair (default 64)
//   --threads N        worker threads (default: all cores); the result does not depend on it
//   --quiet            no progress on stderr
// Before any pair is computed, the matrix's memory and --out's size are estimated from a sample of
// pairs, the number of surfaces and the format (view_factor_work.h); work beyond the machine's memory or
// the disk's free space is refused with the estimate and the option to change.
// Progress (pairs done, elapsed, time left) goes to stderr every 2 s on long runs; a summary to
// stdout. Bad options and files are a one-line error naming the option or file:line, before any
// work; outputs are written atomically and never replace an input.
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "commands.h"
#include "hrad/core/error.h"
#include "hrad/core/memory.h"
#include "hrad/io/atomic_file.h"
#include "hrad/io/points_csv.h"
#include "hrad/io/scene_reader.h"
#include "hrad/solvers/solve.h"
#include "hrad/viewfactors/boundary_csv.h"
#include "hrad/viewfactors/closure.h"
#include "hrad/viewfactors/matrix_formats.h"
#include "hrad/viewfactors/point_factors.h"
#include "hrad/viewfactors/radiant_exchange.h"
#include "hrad/viewfactors/radiosity_exchange.h"
#include "hrad/viewfactors/view_factor_matrix.h"
#include "hrad/viewfactors/view_factor_report.h"
#include "hrad/viewfactors/view_factor_work.h"
#include "hrad/viewfactors/vs3_file.h"

namespace hrad::cli {
namespace {

double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

// Bytes free for an unprivileged writer on the file system that will hold `path` (0: unknown).
double free_disk_bytes(const std::string& path) {
  std::error_code error;
  const std::filesystem::path dir = std::filesystem::absolute(path, error).parent_path();
  const std::filesystem::space_info space = std::filesystem::space(dir, error);
  return error ? 0.0 : static_cast<double>(space.available);
}

void write_heat_csv(const std::string& path, const SurfaceUnits& units, const std::vector<double>& area,
                    const RadiantExchange& x) {
  write_file_atomically(path, [&](std::ostream& o) {
    o << "surface,name,area,emissivity,temperature,heat_flux,heat_rate,radiosity\n";
    for (int u = 0; u < units.size(); ++u) {
      const auto i = static_cast<std::size_t>(u);
      o << fmt::format("{},{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", u, units.names[i], area[i],
                       units.emissivity[i], x.temperature[i], x.heat_flux[i], x.heat_flux[i] * area[i],
                       x.radiosity[i]);
    }
  });
}

// Options of the matrix and of the solvers: which --method each applies to.
const char* const kMatrixOptions[] = {"--out",           "--format",      "--report",       "--visibility-error",
                                      "--row-error",     "--max-rays",    "--exact",        "--threshold",
                                      "--sample-below",  "--far-rays",    "--enforce-closure", "--write-vs3",
                                      "--points",        "--sky-temperature"};
struct SolverOption {
  const char* name;
  std::vector<Method> methods;
};
const SolverOption kSolverOptions[] = {
    {"--max-area", {Method::kFull, Method::kSubstructure}},
    {"--patch-area", {Method::kSubstructure}},
    {"--feps", {Method::kHierarchical}},
    {"--aeps", {Method::kHierarchical}},
    {"--tolerance", {Method::kSubstructure, Method::kHierarchical}},
    {"--visibility-samples", {Method::kFull, Method::kSubstructure, Method::kHierarchical}},
};

struct Args {
  std::string scene, out, format, by = "face", report, write_vs3, points, boundary, heat, method = "matrix";
  double visibility_error = 0.01, row_error = 0.0, threshold = 0.0, sample_below = 0.0, sky_temperature = 0.0;
  double max_area = 0.0, patch_area = 0.0, feps = 0.0, aeps = 0.0, tolerance = 1e-9;
  int max_rays = 4096, far_rays = 16, threads = 0, visibility_samples = kDefaultVisibilitySamples;
  bool exact = false, enforce_closure = false, quiet = false;
};

// --method full|substructure|hierarchical: the exchange by a radiosity solver, no matrix.
void solve_exchange_command(const CLI::App& cmd, Args& args) {
  if (args.method != "full" && args.method != "substructure" && args.method != "hierarchical")
    throw Error(fmt::format("--method: '{}' is not matrix, full, substructure or hierarchical", args.method));
  SolveOptions o;
  o.method = parse_method(args.method);
  for (const char* name : kMatrixOptions)
    if (cmd.count(name) > 0)
      throw Error(fmt::format("{}: applies to --method matrix; --method {} solves the exchange on its own elements "
                              "(no matrix, the sky at 0 K)",
                              name, args.method));
  for (const SolverOption& s : kSolverOptions)
    if (cmd.count(s.name) > 0 && std::find(s.methods.begin(), s.methods.end(), o.method) == s.methods.end())
      throw Error(fmt::format("{}: does not apply to --method {}", s.name, args.method));
  if (args.by != "face" && args.by != "group") throw Error(fmt::format("--by: '{}' is not face or group", args.by));
  if (args.boundary.empty() || args.heat.empty())
    throw Error(fmt::format("--method {} solves radiant exchange: give --boundary B.csv and --heat Q.csv", args.method));
  for (const auto& [name, value] : {std::pair<const char*, double>{"--max-area", args.max_area},
                                    {"--patch-area", args.patch_area},
                                    {"--feps", args.feps},
                                    {"--aeps", args.aeps},
                                    {"--tolerance", args.tolerance}})
    if (cmd.count(name) > 0 && !(std::isfinite(value) && value > 0.0))
      throw Error(fmt::format("{} must be > 0, got {}", name, value));
  if (args.threads < 0) throw Error(fmt::format("--threads: {} is negative", args.threads));
  o.max_area = args.max_area;
  o.patch_area = args.patch_area;
  o.feps = args.feps;
  o.aeps = args.aeps;
  o.tolerance = args.tolerance;
  o.visibility_samples = args.visibility_samples;
  o.threads = args.threads;
  // Exact unoccluded factors (the closed form): the balance of a closed model rests on its rows' closure.
  o.kernel = FormFactorKernel::kAnalytic;
  if (!args.quiet) o.progress = [](std::string_view line) { std::cerr << "hrad viewfactors: " << line << "\n"; };
  validate_options(o);
  const bool vs3_input = std::filesystem::path(args.scene).extension() == ".vs3";
  if (vs3_input && args.by != "face") throw Error("--by group: a .vs3 model's rows are its surfaces");
  OutputFiles outputs;
  outputs.declare("--heat", args.heat);
  outputs.check_inputs({{"the scene", args.scene}, {"--boundary", args.boundary}});

  std::vector<std::string> warnings;
  ObjReadOptions read_options;
  read_options.progress = o.progress;
  read_options.cut_emitter_planes = false;  // view factors are geometry: no lamp's light to follow,
  read_options.cut_near_faces = false;      // and the faces as given
  Vs3Model model;
  if (vs3_input) {
    model = read_vs3(args.scene, &warnings);
  } else {
    model.scene = read_scene(args.scene, &warnings, read_options);
    model.units = args.by == "group" ? group_units(model.scene) : face_units(model.scene);
  }
  std::vector<std::pair<std::string, std::string>> inputs;
  for (const std::string& f : model.scene.files) inputs.emplace_back("an input of the scene", f);
  outputs.check_inputs(inputs);
  for (const std::string& w : warnings) std::cerr << w << "\n";
  const std::vector<SurfaceCondition> conditions = read_boundary_csv(args.boundary, model.units.size());
  const RadiosityExchange r = solve_exchange_by_radiosity(model.scene, model.units, conditions, o);
  write_heat_csv(args.heat, model.units, model.units.area, r.exchange);
  outputs.commit();
  const SolveSummary& sum = r.summary;
  std::cout << fmt::format(
      "{}: radiant exchange by {}: {} surfaces, {} elements, {} links; {}; net heat leaving all surfaces {:.6g} W "
      "(0 in a closed model; an open one's loss to the sky); {:.3f} s, peak memory {:.0f} MB\n",
      model.scene.path, to_string(sum.method), model.units.size(), sum.elements, sum.links, sum.message,
      r.exchange.sky_heat, sum.total_seconds, peak_memory_mb());
}
}  // namespace

void add_viewfactors_command(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("viewfactors", "Obstructed view-factor matrix between faces or groups (thermal radiation)");
  auto args = std::make_shared<Args>();
  cmd->add_option("SCENE", args->scene, "Scene file (.obj, .ply, .gltf, .glb)")->required();
  cmd->add_option("--out", args->out, "Write the matrix here (.csv dense, .mtx, .txt View3D layout)");
  cmd->add_option("--write-vs3", args->write_vs3, "Also write the scene as View3D input (.vs3)");
  cmd->add_option("--format", args->format, "dense | triplets | mtx | view3d (default: by extension)");
  cmd->add_option("--by", args->by, "face (default) or group");
  cmd->add_option("--report", args->report, "Write the JSON report here");
  cmd->add_option("--visibility-error", args->visibility_error,
                  "Target standard error of partly visible fractions (default 0.01)");
  cmd->add_option("--row-error", args->row_error,
                  "Target standard error of each row sum (allocates rays; default off)");
  cmd->add_option("--max-rays", args->max_rays, "Most point pairs per partly visible pair (default 4096)");
  cmd->add_flag("--exact", args->exact, "Partly visible pairs by the exact visible region");
  cmd->add_option("--threshold", args->threshold, "Drop pairs whose unobstructed factor is below this (default 0)");
  cmd->add_option("--sample-below", args->sample_below,
                  "Sample pairs whose unobstructed factor is below this without a shaft test (default 0)");
  cmd->add_option("--far-rays", args->far_rays, "Point pairs per --sample-below pair (default 16)");
  cmd->add_flag("--enforce-closure", args->enforce_closure,
                "Adjust a closed model's rows to sum to 1, keeping reciprocity");
  cmd->add_option("--points", args->points, "Probe points (CSV x,y,z,nx,ny,nz): point-to-surface factors to --out");
  cmd->add_option("--boundary", args->boundary, "Radiant exchange: conditions (CSV surface,temperature,heat_flux)");
  cmd->add_option("--heat", args->heat, "Radiant exchange: write net heat per surface here (CSV)");
  cmd->add_option("--sky-temperature", args->sky_temperature, "Sky temperature, K (default 0)");
  cmd->add_option("--method", args->method,
                  "Radiant exchange by: matrix (default) | full | substructure | hierarchical");
  cmd->add_option("--max-area", args->max_area, "Full/substructure: largest element area (default total/250)");
  cmd->add_option("--patch-area", args->patch_area, "Substructure: largest shooting-patch area (default total/64)");
  cmd->add_option("--feps", args->feps, "Hierarchical: form-factor tolerance (default 0.01)");
  cmd->add_option("--aeps", args->aeps, "Hierarchical: smallest element area (default total/1000)");
  cmd->add_option("--tolerance", args->tolerance,
                  "Substructure/hierarchical: estimated relative error to stop at (default 1e-9)");
  cmd->add_option("--visibility-samples", args->visibility_samples,
                  "Solvers: point pairs per partly visible pair (default 64)");
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)");
  cmd->add_flag("--quiet", args->quiet, "No progress on stderr");
  cmd->callback([cmd, args] {
    if (args->method != "matrix") {
      solve_exchange_command(*cmd, *args);
      return;
    }
    for (const SolverOption& s : kSolverOptions)
      if (cmd->count(s.name) > 0)
        throw Error(fmt::format("{}: applies to the radiosity solvers (--method full|substructure|hierarchical), "
                                "not to --method matrix",
                                s.name));
    if (args->by != "face" && args->by != "group")
      throw Error(fmt::format("--by: '{}' is not face or group", args->by));
    if (!(args->visibility_error > 0.0 && args->visibility_error < 1.0))
      throw Error(fmt::format("--visibility-error: {} is not in (0, 1)", args->visibility_error));
    if (!(args->row_error >= 0.0 && args->row_error < 1.0))
      throw Error(fmt::format("--row-error: {} is not in [0, 1)", args->row_error));
    if (args->row_error > 0.0 && args->exact)
      throw Error("--row-error and --exact exclude each other (the exact region has no sampling error)");
    if (args->max_rays < 64 || args->max_rays > 1 << 24)
      throw Error(fmt::format("--max-rays: {} is not in [64, 16777216]", args->max_rays));
    if (!(args->threshold >= 0.0 && args->threshold < 1.0))
      throw Error(fmt::format("--threshold: {} is not in [0, 1)", args->threshold));
    if (!(args->sample_below >= 0.0 && args->sample_below < 1.0))
      throw Error(fmt::format("--sample-below: {} is not in [0, 1)", args->sample_below));
    if (args->sample_below > 0.0 && args->exact)
      throw Error("--sample-below and --exact exclude each other (the exact region samples nothing)");
    if (args->far_rays < kMinSampledRays || args->far_rays > 1 << 24)
      throw Error(fmt::format("--far-rays: {} is not in [{}, 16777216]", args->far_rays, kMinSampledRays));
    if (args->threads < 0) throw Error(fmt::format("--threads: {} is negative", args->threads));
    if (args->boundary.empty() != args->heat.empty())
      throw Error(args->heat.empty() ? "--boundary needs --heat Q.csv" : "--heat needs --boundary B.csv");
    if (!args->points.empty() && !args->boundary.empty()) throw Error("--points and --boundary exclude each other");
    if (!(args->sky_temperature >= 0.0))
      throw Error(fmt::format("--sky-temperature: {} K is negative", args->sky_temperature));
    if (args->out.empty() && args->write_vs3.empty()) throw Error("give --out F (and/or --write-vs3 M.vs3)");
    const MatrixFormat format =
        args->out.empty() ? MatrixFormat::kDense : matrix_format(args->format, args->out, "--out");
    const bool vs3_input = std::filesystem::path(args->scene).extension() == ".vs3";
    if (vs3_input && args->by != "face") throw Error("--by group: a .vs3 model's rows are its surfaces");
    if (vs3_input && !args->write_vs3.empty()) throw Error("--write-vs3: the scene is already a .vs3 file");

    OutputFiles outputs;
    if (!args->out.empty()) outputs.declare("--out", args->out);
    if (!args->write_vs3.empty()) outputs.declare("--write-vs3", args->write_vs3);
    if (!args->report.empty()) outputs.declare("--report", args->report);
    if (!args->heat.empty()) outputs.declare("--heat", args->heat);
    std::vector<std::pair<std::string, std::string>> given = {{"the scene", args->scene}};
    if (!args->points.empty()) given.emplace_back("--points", args->points);
    if (!args->boundary.empty()) given.emplace_back("--boundary", args->boundary);
    outputs.check_inputs(given);
    if (!args->points.empty() && args->out.empty()) throw Error("--points needs --out F.csv");
    std::vector<ProbePoint> points;
    if (!args->points.empty()) points = read_points_csv(args->points);

    ViewFactorOptions options;
    options.pair.partial = args->exact ? PartialVisibility::kExactRegion : PartialVisibility::kSampled;
    options.pair.fraction_error = args->visibility_error;
    options.pair.max_rays = args->max_rays;
    options.threshold = args->threshold;
    options.sample_below = args->sample_below;
    options.pair.far_rays = args->far_rays;
    options.row_error = args->row_error;
    options.threads = args->threads;
    if (!args->quiet)
      options.progress = [](std::string_view line) { std::cerr << "hrad viewfactors: " << line << "\n"; };

    std::vector<std::string> warnings;
    ObjReadOptions read_options;
    read_options.progress = options.progress;
    read_options.cut_emitter_planes = false;  // view factors are geometry: no lamp's light to follow,
    read_options.cut_near_faces = false;      // and the faces as given
    Vs3Model model;
    if (vs3_input) {
      model = read_vs3(args->scene, &warnings);
      if (model.enclosure) args->enforce_closure = true;
    } else {
      model.scene = read_scene(args->scene, &warnings, read_options);
      model.units = args->by == "group" ? group_units(model.scene) : face_units(model.scene);
    }
    const Scene& scene = model.scene;
    const SurfaceUnits& units = model.units;
    std::vector<std::pair<std::string, std::string>> inputs;
    for (const std::string& f : scene.files) inputs.emplace_back("an input of the scene", f);
    outputs.check_inputs(inputs);
    for (const std::string& w : warnings) std::cerr << w << "\n";
    if (!args->write_vs3.empty())
      write_file_atomically(args->write_vs3,
                            [&](std::ostream& o) { write_vs3(o, scene, face_units(scene), scene.path); });
    if (args->out.empty()) {
      outputs.commit();
      std::cout << fmt::format("{}: wrote {}\n", scene.path, args->write_vs3);
      return;
    }

    if (!args->points.empty()) {
      const PointFactors pf = point_view_factors(scene, units, points, args->threads, options.progress);
      write_file_atomically(args->out, [&](std::ostream& o) {
        std::string line;
        for (int i = 0; i < pf.points; ++i) {
          line.clear();
          for (int u = 0; u < pf.units; ++u)
            fmt::format_to(std::back_inserter(line), "{}{:.17g}", u ? "," : "", pf.at(i, u));
          o << line << "\n";
        }
      });
      outputs.commit();
      std::cout << fmt::format(
          "{}: {} points x {} surfaces; point-patch pairs {} visible, {} hidden, {} partial (exact regions)\n",
          scene.path, pf.points, pf.units, pf.visible, pf.hidden, pf.partial);
      return;
    }
    std::vector<SurfaceCondition> conditions;
    if (!args->boundary.empty()) conditions = read_boundary_csv(args->boundary, units.size());

    // Refused before any pair is computed when the machine cannot hold the matrix or its output.
    const double memory = available_memory_bytes(), disk = free_disk_bytes(args->out);
    ViewFactorWork work;
    options.before_pairs = [&](const PairSample& sample) {
      work = estimate_view_factor_work(sample, units.size(), static_cast<double>(scene.patches.size()), format);
      check_view_factor_work(work, options, format, args->out, memory, disk);
    };
    ViewFactorMatrix m = compute_view_factors(scene, units, options);
    ClosureReport closure;
    if (args->enforce_closure) closure = enforce_closure(m);
    write_file_atomically(args->out, [&](std::ostream& o) { write_matrix(o, m, units, format); });
    nlohmann::json report = view_factor_report(m, units, options, args->enforce_closure ? &closure : nullptr);
    report["estimate"] = {
        {"stored_pairs", work.stored_pairs}, {"memory_bytes", work.memory_bytes}, {"output_bytes", work.output_bytes}};
    if (!conditions.empty()) {
      const RadiantExchange x = solve_radiant_exchange(m, units.emissivity, conditions, args->sky_temperature);
      write_heat_csv(args->heat, units, m.area, x);
    }
    if (!args->report.empty())
      write_file_atomically(args->report, [&](std::ostream& o) { o << report.dump(2) << "\n"; });
    outputs.commit();
    std::cout << fmt::format(
        "{}: {} surfaces, {} nonzeros; pairs {} ({} dropped below {}, {} visible, {} hidden, {} partial of which {} "
        "sampled without a shaft test, {} facing away); row sums {:.12g}..{:.12g}, max reciprocity error {:.3g}, max "
        "row sampling error {:.3g}, max dropped bound {:.3g}; {} rays; {:.3f} s, peak memory {:.0f} MB\n",
        scene.path, m.n, m.nonzeros(), m.counters.patch_pairs, m.counters.skipped_pairs, args->threshold,
        m.counters.fully_visible, m.counters.fully_hidden, m.counters.partial, m.counters.shaft_skipped,
        m.counters.facing_away, report["min_row_sum"].get<double>(), report["max_row_sum"].get<double>(),
        report["max_reciprocity_error"].get<double>(), report["max_sampling_error"].get<double>(),
        report["max_skipped_bound"].get<double>(), m.counters.rays, m.counters.seconds, peak_memory_mb());
    if (args->enforce_closure)
      std::cout << fmt::format(
          "closure: rows off by up to {:.3g} before, {:.3g} after; largest factor change {:.3g}, {:.3g} of the "
          "exchange moved\n",
          closure.max_row_error_before, closure.max_row_error_after, closure.max_factor_change,
          closure.relative_change);
  });
}

}  // namespace hrad::cli
