// hrad solve SCENE [--method full|substructure|hierarchical] [options] [--report R.json] [--out S.ply]
//
// Solves the radiosity of a scene (OBJ + MTL) and writes a report and the leaf mesh. Both outputs
// are optional; they are checked before any work (never an input of the scene, never the same file,
// a regular file or a new path in a writable folder) and written together at the end, atomically;
// progress goes to stderr, a summary to stdout.
//
//   --method M             full (classical, n x n matrix), substructure (patches shoot, elements
//                          receive) or hierarchical (HSA 1991 quadtrees and links); default hierarchical
//   --max-area A           full/substructure: largest element area, scene units^2
//                          (default: total area / 250)
//   --patch-area A         substructure: largest shooting-patch area (default: total area / 64; the largest input area
//   keeps the input polygons)
//   --feps F               hierarchical: form-factor refinement tolerance (default automatic)
//   --bfeps B              hierarchical: B*F refinement tolerance (radiosity units; default unused)
//   --aeps A               hierarchical: smallest element area (default automatic)
//   --source-levels N      hierarchical (HSA push): quadtree levels below --aeps to which a source
//                          element may still split where a receiver's kernel peaks over part of it
//                          and its reflected radiosity may vary there: contacts, the inside of a
//                          lamp's housing (default 0: --aeps bounds every split); auto: 2 levels on
//                          the patches near bright lamps only (core/bright_emitters.h)
//   --tolerance T          iterations stop when the estimated error of the answer is below T,
//                          relative both to the largest reflected radiosity and to the reflected
//                          power: the last change times q / (1 - q), q the contraction per
//                          iteration estimated from successive changes (default 1e-6)
//   --max-iterations N     iteration limit (default 10000); reaching it is a status, not an error
//   --linear-solver S      full: lu (default, direct), jacobi or gauss_seidel; with --basis linear
//                          jacobi (the default there, the only one offered)
//   --effects auto|all     auto (default) simulates only what the scene needs (visibility, colour,
//                          bounces); all forces everything on (same answer, slower)
//   --kernel contour|analytic
//                          unoccluded form factors: contour (default: Gauss points on the receiver,
//                          Lambert's exact point-to-polygon formula) or analytic (closed-form
//                          polygon-to-polygon, ~1e-13, much slower); full and substructure only:
//                          hierarchical radiosity always uses analytic (the report says so)
//   --visibility-samples K point pairs per partially visible pair (default 64)
//   --seed S               the sample stream (default 0): other values draw independent samples of
//                          the same estimators, so a result's spread over seeds is its sampling noise
//   --power-noise S        hierarchical: the standard deviation over sample streams the power
//                          balance should have (default 0: the default sampling)
//   --closure auto|off     hierarchical, HSA push: auto (default) closes every leaf's sends to 1
//                          where rays drawn by the solve's power find no opening and no back
//                          (lib/hrad/solvers/closed_scene.h); off leaves the links' sampled closure
//   --clustering auto|on|off
//                          hierarchical: a cluster hierarchy above the input polygons, linked from
//                          one root self-link (Smits, Arvo & Greenberg 1994), or plain HSA with every
//                          pair of input polygons linked first; auto (default) clusters from 200 patches
//   --push hsa|leaf        hierarchical: hsa (default) gathers each link at the nodes it joins and
//                          pushes down (O(links) per iteration); leaf resolves element links to the
//                          leaves on both sides with their own factors (exact per element in closed
//                          rooms, one term per leaf and link on its path)
//   --basis constant|linear
//                          the radiosity over each element: constant (default), or linear (bilinear
//                          on quads), the L2 projection of E + rho H (every method, either push;
//                          lib/hrad/solvers/linear_basis.h, field_links.h, leaf_links.h)
//   --balance              balance the leaves after meshing or refinement (a restricted quadtree: at
//                          most one level between edge neighbours, so no long T-edges in the output)
//   --no-cut-near-faces    keep faces whole that the reader cuts by default along the outlines of
//                          parallel faces facing them from at most a tenth of their size
//                          (lib/hrad/io/near_faces.h; the faces stay, their patches multiply), and
//                          warn of such pairs instead. The solution PLY says so, and render/probe read alike
//   --threads N            worker threads (default: all cores)
//   --report R.json        the solve report (see lib/hrad/report/report_json.h)
// Every solve prints where the power went (reference/power_balance.h): emitted, absorbed, onto
// backs, escaped (the last ones sampled with rays of the reference's own), and the residual; a
// residual above kPowerBalanceTolerance of the emitted power (plus 4 standard errors of the sampled
// terms) is a warning on stderr and in the report.
//   --out S.ply            the leaf mesh with tone-mapped vertex colours and per-face radiosity; a
//                          hierarchical solve's file also carries its element hierarchy and links, which
//                          hrad render --final-gather and hrad probe gather through (io/solution_ply.h)
//   --exposure X           vertex-colour exposure for --out (default: automatic, emitters excluded)
//   --quiet                no progress on stderr
// Options out of range (zero, negative or NaN tolerances and areas, unknown names) are an error
// with exit status 1 before the scene is read.
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "commands.h"
#include "hrad/core/error.h"
#include "hrad/core/scene_checks.h"
#include "hrad/core/tone_map.h"
#include "hrad/gather/stored_links.h"
#include "hrad/io/atomic_file.h"
#include "hrad/io/near_faces.h"
#include "hrad/io/scene_reader.h"
#include "hrad/io/solution_ply.h"
#include "hrad/report/report_json.h"
#include "hrad/solvers/solve.h"
#include "hrad/solvers/solved_hierarchy.h"
#include "seed_option.h"

namespace hrad::cli {

namespace {

// What to try when a solve does not balance power, from what it used (README "Limits").
std::string balance_advice(const SolveSummary& summary) {
  const SolveOptions& used = summary.used;
  if (summary.termination == Termination::kMaxIterations)
    return "the iterations stopped at --max-iterations before converging: raise it";
  std::string advice = summary.method == Method::kHierarchical ? "refine (--feps, --aeps)"
                       : used.kernel == FormFactorKernel::kAnalytic || used.basis == Basis::kLinear
                           ? "refine (--max-area)"
                           : "refine (--max-area) or try --kernel analytic";
  if (used.basis == Basis::kLinear)
    advice += "; linear elements do not balance where a source is closer than an element's size: try --basis constant";
  return advice;
}

}  // namespace

void add_solve_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("solve", "Solve the radiosity of a scene (full, substructure or hierarchical)");
  struct Args {
    std::string scene, method = "hierarchical", linear_solver = "lu", effects = "auto", kernel = "contour",
                       clustering = "auto", closure = "auto", push = "hsa", basis = "constant", report, out;
    double max_area = 0.0, patch_area = 0.0, feps = 0.0, bfeps = 0.0, aeps = 0.0, tolerance = 1e-6, exposure = 0.0,
           power_noise = 0.0;
    int max_iterations = 10000, visibility_samples = kDefaultVisibilitySamples, threads = 0;
    std::uint64_t seed = 0;
    std::string source_levels = "0";
    bool quiet = false, balance = false, keep_near_faces = false;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("SCENE", args->scene, "Scene file (.obj)")->required();
  cmd->add_option("--method", args->method, "full | substructure | hierarchical (default hierarchical)");
  cmd->add_option("--max-area", args->max_area, "Full/substructure: largest element area (default total/250)");
  cmd->add_option("--patch-area", args->patch_area,
                  "Substructure: largest shooting-patch area (default total area / 64)");
  cmd->add_option("--feps", args->feps, "Hierarchical: form-factor tolerance (default automatic)");
  cmd->add_option("--bfeps", args->bfeps, "Hierarchical: B*F tolerance (default unused)");
  cmd->add_option("--aeps", args->aeps, "Hierarchical: smallest element area (default automatic)");
  cmd->add_option("--source-levels", args->source_levels,
                  "Hierarchical: levels below --aeps a source may split to where a receiver's kernel peaks over "
                  "part of it (contacts, lamp housings), or auto: 2 levels on the patches near bright lamps only "
                  "(default 0)");
  cmd->add_option("--tolerance", args->tolerance,
                  "Stop when the estimated relative error (last change x q/(1-q), q the contraction) of the brightest "
                  "leaf and of the reflected power is below this (default 1e-6)");
  cmd->add_option("--max-iterations", args->max_iterations, "Iteration limit (default 10000)");
  auto* linear_solver = cmd->add_option("--linear-solver", args->linear_solver,
                                        "Full: lu | jacobi | gauss_seidel (default lu; with --basis linear jacobi)");
  cmd->add_option("--effects", args->effects, "auto | all (default auto)");
  cmd->add_option(
      "--kernel", args->kernel,
      "Full/substructure: form-factor kernel: contour (default) | analytic (hierarchical: always analytic)");
  cmd->add_option("--visibility-samples", args->visibility_samples,
                  "Point pairs per partially visible pair (default 64; hierarchical links scale their own counts by it "
                  "/ 64, at least 4)");
  cmd->add_option("--seed", args->seed,
                  "Sample stream (default 0): another value draws independent samples of every sampled "
                  "quantity, so the spread of a result over seeds is its sampling noise")
      ->check(cli::seed_validator());
  cmd->add_option("--power-noise", args->power_noise,
                  "Hierarchical: the standard deviation over --seed streams the power balance should have, e.g. 2.5e-4 "
                  "(more point pairs and cluster rays where the power flows; default 0: the default sampling)");
  cmd->add_option("--closure", args->closure,
                  "Hierarchical, HSA push: auto (default: where rays drawn by the solve's power find no opening and "
                  "no back, every leaf's sends are closed to 1 and the power balances by construction) | off");
  cmd->add_option("--clustering", args->clustering,
                  "Hierarchical: auto | on | off (default auto: on from 200 patches)");
  cmd->add_option("--push", args->push,
                  "Hierarchical: hsa (default, O(links) gather) | leaf (links resolved to leaves)");
  cmd->add_option("--basis", args->basis, "Radiosity per element: constant (default) | linear (bilinear on quads)");
  cmd->add_flag("--balance", args->balance, "At most one level between edge neighbours (no long T-edges)");
  cmd->add_flag("--no-cut-near-faces", args->keep_near_faces,
                "Keep faces whole that are cut by default along the outlines of parallel faces facing them from "
                "nearby (a box 1 cm above the floor, a cabinet 1 mm from its wall), and warn of such pairs");
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)");
  cmd->add_option("--report", args->report, "Write the solve report (JSON) here");
  cmd->add_option("--out", args->out, "Write the leaf mesh (PLY) here");
  cmd->add_option("--exposure", args->exposure, "Vertex-colour exposure for --out (default automatic)");
  cmd->add_flag("--quiet", args->quiet, "No progress on stderr");
  cmd->callback([cmd, args, linear_solver] {
    SolveOptions o;
    o.method = parse_method(args->method);
    // Linear elements iterate their corner values: Jacobi unless the option says otherwise.
    o.linear_solver =
        parse_linear_solver(args->basis == "linear" && linear_solver->count() == 0 ? "jacobi" : args->linear_solver);
    o.effects = parse_effects_mode(args->effects);
    o.kernel = parse_kernel(args->kernel);
    o.clustering = parse_clustering(args->clustering);
    o.push = parse_push(args->push);
    o.basis = parse_basis(args->basis);
    o.balance = args->balance;
    // Given on the command line, an area or tolerance must be a positive number (0 is "automatic"
    // only when the option is left out).
    for (const auto& [name, value] : {std::pair<const char*, double>{"--max-area", args->max_area},
                                      {"--patch-area", args->patch_area},
                                      {"--feps", args->feps},
                                      {"--bfeps", args->bfeps},
                                      {"--aeps", args->aeps},
                                      {"--tolerance", args->tolerance},
                                      {"--exposure", args->exposure}}) {
      if (cmd->count(name) > 0 && !(std::isfinite(value) && value > 0.0))
        throw Error(fmt::format("{} must be > 0, got {}", name, value));
    }
    o.max_area = args->max_area;
    o.patch_area = args->patch_area;
    o.feps = args->feps;
    o.bfeps = args->bfeps;
    o.aeps = args->aeps;
    const SourceLevels levels = parse_source_levels(args->source_levels);
    o.source_levels = levels.levels;
    o.source_levels_near_lamps = levels.near_lamps;
    o.tolerance = args->tolerance;
    o.max_iterations = args->max_iterations;
    o.visibility_samples = args->visibility_samples;
    o.seed = args->seed;
    o.power_noise = args->power_noise;
    if (args->closure != "auto" && args->closure != "off")
      throw Error(fmt::format("--closure must be auto or off, got '{}'", args->closure));
    o.close_closed_scenes = args->closure == "auto";
    o.threads = args->threads;
    if (!args->quiet) o.progress = [](std::string_view line) { std::cerr << "hrad solve: " << line << "\n"; };
    validate_options(o);
    // Outputs are checked before any work and written together at the end (io/atomic_file.h).
    OutputFiles outputs;
    if (!args->report.empty()) outputs.declare("--report", args->report);
    if (!args->out.empty()) outputs.declare("--out", args->out);
    outputs.check_inputs({{"the scene", args->scene}});

    std::vector<std::string> warnings;
    ObjReadOptions read_options;
    read_options.progress = o.progress;
    read_options.cut_near_faces = !args->keep_near_faces;
    const Scene scene = read_scene(args->scene, &warnings, read_options);
    for (const std::string& w : scene_warnings(scene)) warnings.push_back(scene.path + ": warning: " + w);
    if (args->keep_near_faces)
      if (std::string w = near_faces_warning(scene); !w.empty()) warnings.push_back(std::move(w));
    for (const std::string& w : warnings) std::cerr << w << "\n";
    std::vector<std::pair<std::string, std::string>> inputs;
    for (const std::string& f : scene.files) inputs.emplace_back("an input of the scene", f);
    outputs.check_inputs(inputs);
    Solution solution;
    // A hierarchical solve's links go into --out, for a final gather through them.
    SolvedHierarchy kept;
    const bool keep = !args->out.empty() && o.method == Method::kHierarchical;
    const SolveSummary summary = solve(scene, o, &solution, keep ? &kept : nullptr);
    // Where the power went, checked with rays of the reference's own (reference/power_balance.h). The
    // check needs an Embree device, which a tight address-space limit (ulimit -v) can refuse after the
    // solve succeeded: then the solution is still written, with a warning instead of the power line.
    std::optional<PowerBalance> balance;
    std::string balance_line;
    try {
      balance = power_balance(scene, solution);
    } catch (const Error& e) {
      warnings.push_back(fmt::format("{}: warning: power balance not checked ({})", scene.path, e.what()));
      std::cerr << warnings.back() << "\n";
    }
    if (balance) {
      const double emitted = balance->emitted.mean();
      const auto share = [&](const Rgb& v) { return emitted > 0.0 ? v.mean() / emitted : 0.0; };
      balance_line = fmt::format(
          "power: emitted {:.6g}; absorbed {:.6f} (reflecting surfaces {:.6f}, black {:.6f}), onto backs {:.6f}, "
          "escaped {:.6f} (sampled, standard error {:.2g}); residual {:.3g} of the emitted power",
          emitted, share(balance->absorbed_reflecting + balance->absorbed_black), share(balance->absorbed_reflecting),
          share(balance->absorbed_black), share(balance->onto_backs), share(balance->escaped),
          share(balance->sampled_se), share(balance->residual));
      if (!balance->balanced()) {
        warnings.push_back(
            fmt::format("{}: warning: the solution does not balance power: {} of the emitted power is unaccounted for "
                        "in its worst colour channel (the power line gives the channels' mean; allowed {:.3g}: "
                        "{} plus {} standard errors); {}",
                        scene.path, fmt::format("{:.3g}", balance->relative_residual()), balance->allowed(),
                        kPowerBalanceTolerance, kPowerBalanceStandardErrors, balance_advice(summary)));
        std::cerr << warnings.back() << "\n";
      }
    }

    if (!args->report.empty()) {
      nlohmann::json report = solve_report_json(scene, o, summary, solution);
      report["options"]["cut_near_faces"] = !args->keep_near_faces;
      report["power_balance"] = balance ? power_balance_json(*balance) : nlohmann::json(nullptr);
      report["warnings"] = warnings;  // the reader's and the scene checks', as printed on stderr
      write_json_file(args->report, report);
    }
    if (!args->out.empty()) {
      double exposure = args->exposure;
      if (exposure <= 0.0) {
        std::vector<bool> emitter(scene.patches.size());
        for (std::size_t p = 0; p < scene.patches.size(); ++p)
          emitter[p] = scene.material_of(scene.patches[p]).is_emitter();
        exposure = auto_exposure(solution, emitter);
      }
      std::optional<SolutionLinks> links;
      if (kept.hierarchy) links = stored_links(kept);
      solution.near_faces_cut = !args->keep_near_faces;
      write_solution_ply(args->out, solution, exposure, links ? &*links : nullptr);
    }
    outputs.commit();
    std::cout << fmt::format("{}: {} on {} patches: {} elements, {} links, {} form factors, {} visibility queries\n",
                             scene.path, to_string(summary.method), summary.patches, summary.elements, summary.links,
                             summary.form_factor_evaluations, summary.visibility_queries);
    std::cout << fmt::format("  {}: {}\n", to_string(summary.termination), summary.message);
    if (balance) std::cout << "  " << balance_line << "\n";
    std::string phases;
    for (const auto& [name, s] : summary.seconds) phases += fmt::format(" {} {:.3f}", name, s);
    std::cout << fmt::format("  seconds: total {:.3f} ({} )\n", summary.total_seconds, phases);
    for (const std::string& r : summary.effects.reasons) std::cout << "  effects: " << r << "\n";
  });
}

}  // namespace hrad::cli
