// hrad sweep SCENE --out DIR [--quick] [--reference-elements N | --reference-from DIR] [--samples N]
//            [--target-error E] [--threads N]
//
// What accuracy costs in time. Runs each method over its accuracy parameter, from coarse to fine:
//   full          element size (max_area = total area / n, n = 64 .. 9000), Gauss-Seidel
//   substructure  element size (the same n, input polygons shoot) and shooting-patch size
//   hierarchical  feps (0.3 .. 0.001, aeps automatic) and aeps (1e-2 .. 1.5e-5 of the total area),
// each once per basis (--basis: constant, and linear as methods full_linear (Jacobi),
// substructure_linear and hierarchical_linear)
// and judges every run against one reference (a full-matrix LU solve, 4 x the finest full run and at
// most 4096 elements unless --reference-elements, final-gathered at the error samples) on fixed
// samples on every surface. Writes:
//   DIR/sweep.csv       one row per run: method, parameter, value, elements, links,
//                       form_factor_evaluations, visibility_queries, seconds, error_l2, error_linf, ...,
//                       and error_l2_gathered, error_linf_gathered: the run's own final gather at the
//                       samples (what a gathered image or probe shows) with its cost, gather_seconds
//                       and gather_work (point factors, classifications, rays), not in seconds
//   DIR/reference.json  how the reference was made
//   DIR/reference_samples.json  the reference's final gather at the error samples; --reference-from
//                       DIR reads it back (with reference.json) instead of solving the reference again
//   DIR/fit.json        Ceres fits: seconds ~ a n^b and links ~ c n^alpha per method, error ~ k feps^beta
//                       for hierarchical; the time each method needs to reach --target-error (default 1%)
//                       and the full/hierarchical ratio
//   DIR/pareto.png      error against time, log-log, the three methods
//   DIR/command.txt     the command that made them
// --quick runs a short sweep that still brackets 1% on the Cornell box (its settings below).
// --no-gather skips the runs' gathers (gathered columns nan); --gather-tolerance T sets their
// Barnes-Hut tolerance (default 1e-2, lib/hrad/gather/leaf_gather.h); hierarchical runs gather
// through their own links (lib/hrad/gather/link_gather.h) unless --gather-sources all. Progress,
// each solve's included, goes to stderr.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "comma_numbers.h"
#include "commands.h"
#include "hrad/core/error.h"
#include "hrad/experiments/reference_samples.h"
#include "hrad/experiments/sweep.h"
#include "hrad/io/atomic_file.h"
#include "hrad/io/near_faces.h"
#include "hrad/io/scene_reader.h"
#include "hrad/report/report_json.h"
#include "hrad/solvers/work_estimate.h"
#include "plot.h"
#include "progress_bar.h"

namespace hrad::cli {
namespace {

// "a,b,c" as numbers in [lo, hi]; empty text gives an empty list (the default settings).
std::vector<double> parse_list(const std::string& option, const std::string& text, double lo, double hi) {
  if (text.empty()) return {};
  const std::optional<std::vector<double>> values = comma_numbers(text);
  const auto outside = [&](double x) { return !(x >= lo && x <= hi); };
  if (!values || std::any_of(values->begin(), values->end(), outside))
    throw Error(fmt::format("{}: expected comma-separated numbers in [{:g}, {:g}], got '{}'", option, lo, hi, text));
  return *values;
}

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("sweep", "Run every method over its accuracy parameter; error against time");
  struct Args {
    std::string scene, out;
    bool quick = false;
    double reference_elements = 0.0, target_error = 0.01, feps_aeps = 0.0;
    int samples = 256, threads = 0;
    std::string elements, patches, feps, aeps, reference_from, push = "hsa", basis = "constant,linear";
    int visibility_samples = 0;
    std::string source_levels = "0";
    bool no_gather = false, keep_near_faces = false;
    double gather_tolerance = 1e-2;
    std::string gather_sources = "links";
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("SCENE", args->scene, "Scene file (.obj)")->required();
  cmd->add_option("--out", args->out, "Output folder")->required();
  cmd->add_flag("--quick", args->quick,
                "A short sweep: 64, 256 and 1024 elements, aeps 1e-3, 1e-4 and 3e-5, against a 1024-element "
                "reference at 64 samples a patch");
  cmd->add_option("--reference-elements", args->reference_elements,
                  "Elements of the reference mesh (default 4 x the finest full run, at most 4096)");
  cmd->add_option("--reference-from", args->reference_from,
                  "Reuse the reference of an earlier sweep of this scene (its output folder)");
  cmd->add_option("--samples", args->samples, "Error samples per patch (default 256; 64 with --quick)");
  cmd->add_option("--target-error", args->target_error, "Relative L2 error for the time-to-error ratio (default 0.01)");
  cmd->add_flag("--no-cut-near-faces", args->keep_near_faces,
                "Keep faces whole that are cut by default along the outlines of parallel faces facing them from "
                "nearby, as hrad solve --no-cut-near-faces does");
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)");
  cmd->add_option("--elements", args->elements, "Element counts of the full and substructuring runs, e.g. 64,128,256");
  cmd->add_option("--patches", args->patches, "Shooting-patch counts of the substructuring patch-size runs");
  cmd->add_option("--feps", args->feps, "Hierarchical form-factor tolerances");
  cmd->add_option("--aeps", args->aeps, "Hierarchical smallest-element areas as fractions of the total area");
  cmd->add_option("--feps-aeps", args->feps_aeps,
                  "The smallest-element area of the feps runs, as a fraction of the total area (default automatic)");
  cmd->add_option("--push", args->push, "Hierarchical link operators to run, comma-separated: hsa, leaf (default hsa)");
  cmd->add_option("--basis", args->basis,
                  "Bases to run for every method and push, comma-separated: constant, linear (default "
                  "constant,linear)");
  cmd->add_option("--visibility-samples", args->visibility_samples,
                  "Point pairs per partly visible pair in every run (default: the solvers'); the reference uses 4x");
  cmd->add_option("--source-levels", args->source_levels,
                  "Hierarchical runs: levels below aeps a source may split to where a receiver's kernel peaks over "
                  "part of it, or auto: 2 levels near bright lamps only (default 0)");
  cmd->add_flag("--no-gather", args->no_gather, "Do not final-gather the runs (error_l2_gathered is nan)");
  cmd->add_option("--gather-tolerance", args->gather_tolerance,
                  "Barnes-Hut tolerance of the runs' final gather, relative to the mean radiosity (default 1e-2)");
  cmd->add_option("--gather-sources", args->gather_sources,
                  "What the hierarchical runs gather over: links (their own links' sources) or all (every patch, "
                  "as the other methods; default links)");
  cmd->callback([args, cmd] {
    if (args->gather_sources != "links" && args->gather_sources != "all")
      throw Error(fmt::format("--gather-sources must be links or all, got '{}'", args->gather_sources));
    if (args->no_gather && cmd->count("--gather-sources")) throw Error("--gather-sources: not with --no-gather");
    if (!(args->gather_tolerance >= 0.0 && std::isfinite(args->gather_tolerance)))
      throw Error(fmt::format("--gather-tolerance: {} is not a finite number >= 0", args->gather_tolerance));
    if (args->no_gather && cmd->count("--gather-tolerance")) throw Error("--gather-tolerance: not with --no-gather");
    if (!(args->samples >= 1 && args->samples <= 1'000'000))
      throw Error(fmt::format("--samples must be in [1, 1e6], got {}", args->samples));
    if (!(args->target_error > 0 && args->target_error < 1))
      throw Error(fmt::format("--target-error must be in (0, 1), got {}", args->target_error));
    if (!(args->reference_elements >= 0 && args->reference_elements <= 1e6))
      throw Error(fmt::format("--reference-elements must be in [0, 1e6], got {}", args->reference_elements));
    if (!args->reference_from.empty() && args->reference_elements > 0)
      throw Error("--reference-from and --reference-elements exclude each other (the reference is read, not solved)");
    if (args->threads < 0) throw Error(fmt::format("--threads must be >= 0, got {}", args->threads));
    // The reference uses 4x: at most the solvers' kMaxVisibilitySamples.
    if (args->visibility_samples < 0 || args->visibility_samples > kMaxVisibilitySamples / 4)
      throw Error(fmt::format("--visibility-samples must be in [0, {}], got {}", kMaxVisibilitySamples / 4,
                              args->visibility_samples));
    // A list option given on the command line must hold at least one number ("--elements ''" is a typo,
    // not "the defaults").
    for (const auto& [name, text] : {std::pair{"--elements", args->elements},
                                     {"--patches", args->patches},
                                     {"--feps", args->feps},
                                     {"--aeps", args->aeps}})
      if (cmd->count(name) > 0 && text.empty())
        throw Error(fmt::format("{}: expected comma-separated numbers, got ''", name));
    const auto elements = parse_list("--elements", args->elements, 1.0, 1e6);
    const auto patches = parse_list("--patches", args->patches, 1.0, 1e6);
    const auto feps = parse_list("--feps", args->feps, 1e-9, 1.0);
    const auto aeps = parse_list("--aeps", args->aeps, 1e-12, 1.0);
    const std::string dir = args->out;
    OutputFiles outputs;
    for (const char* name :
         {"sweep.csv", "reference.json", "reference_samples.json", "fit.json", "command.txt", "pareto.png"})
      outputs.declare("--out", dir + "/" + name);
    std::vector<std::pair<std::string, std::string>> inputs = {{"the scene", args->scene}};
    if (!args->reference_from.empty())
      for (const char* name : {"reference.json", "reference_samples.json"})
        inputs.emplace_back("an input of --reference-from", args->reference_from + "/" + name);
    outputs.check_inputs(inputs);
    std::vector<std::string> warnings;
    ObjReadOptions read_options;
    read_options.cut_near_faces = !args->keep_near_faces;
    const Scene scene = read_scene(args->scene, &warnings, read_options);
    if (args->keep_near_faces)
      if (std::string w = near_faces_warning(scene); !w.empty()) warnings.push_back(std::move(w));
    for (const auto& w : warnings) std::cerr << w << "\n";
    inputs.clear();
    for (const std::string& f : scene.files) inputs.emplace_back("an input of the scene", f);
    outputs.check_inputs(inputs);
    require_plotting();  // last of the checks: the sweep ends in its plot

    SweepOptions options;
    options.samples_per_patch = args->samples;
    options.threads = args->threads;
    options.reference_elements = args->reference_elements;
    if (args->quick) {
      // Each method from coarse to where hierarchical radiosity passes 1% on the Cornell box (linear
      // leaves at aeps 1e-4, the displayed constant field at 3e-5), judged against the finest full
      // run's mesh solved as the reference (LU, 4x the visibility samples, gathered at the samples):
      // the default 4096-element reference and its 8960 gathered samples are most of a full sweep's
      // fixed cost. Options given on the command line override these.
      options.element_counts = {64, 256, 1024};
      options.patch_counts = {double(scene.patches.size()), 4.0 * scene.patches.size()};
      options.feps_values = {0.3, 0.03};
      options.aeps_fractions = {1e-3, 1e-4, 3e-5};
      if (args->reference_from.empty()) {  // a reused reference keeps its own samples
        if (cmd->count("--samples") == 0) options.samples_per_patch = 64;
        if (args->reference_elements == 0) options.reference_elements = 1024;
      }
    }
    if (!elements.empty()) options.element_counts = elements;
    if (!patches.empty()) options.patch_counts = patches;
    if (!feps.empty()) options.feps_values = feps;
    if (!aeps.empty()) options.aeps_fractions = aeps;
    options.visibility_samples = args->visibility_samples;
    const SourceLevels levels = parse_source_levels(args->source_levels);
    options.source_levels = levels.levels;
    options.source_levels_near_lamps = levels.near_lamps;
    options.gather_runs = !args->no_gather;
    options.gather_tolerance = args->gather_tolerance;
    options.gather_through_links = args->gather_sources == "links";
    if (!(args->feps_aeps >= 0.0 && args->feps_aeps < 1.0))
      throw Error(fmt::format("--feps-aeps must be in [0, 1), got {}", args->feps_aeps));
    options.feps_aeps_fraction = args->feps_aeps;
    options.pushes.clear();
    {
      std::stringstream list(args->push);
      std::string item;
      while (std::getline(list, item, ',')) options.pushes.push_back(parse_push(item));
      if (options.pushes.empty()) throw Error("--push: expected hsa, leaf or hsa,leaf, got ''");
    }
    options.bases.clear();
    {
      std::stringstream list(args->basis);
      std::string item;
      while (std::getline(list, item, ',')) options.bases.push_back(parse_basis(item));
      if (options.bases.empty()) throw Error("--basis: expected constant, linear or constant,linear, got ''");
    }
    options.progress = show_progress;
    options.solve_progress = [](std::string_view line) { show_line(fmt::format("sweep: {}", line)); };

    Reference reference;
    if (!args->reference_from.empty()) {
      reference = read_reference_samples(args->reference_from, scene, options.samples_per_patch);
      std::cerr << fmt::format("sweep: reference from {} ({} samples)\n", args->reference_from,
                               reference.gathered.size());
    } else {
      std::cerr << fmt::format("sweep: reference ({:g} elements aimed at, full matrix, LU)...\n",
                               reference_elements_aimed(options));
      reference = make_reference(scene, options);
      std::cerr << fmt::format("sweep: reference took {:.2f} s\n", reference.summary.total_seconds);
    }
    const std::vector<SweepRow> rows = run_sweep(scene, reference, options);
    const nlohmann::json fits = sweep_fits(rows, args->target_error);

    write_file_atomically(dir + "/sweep.csv", [&](std::ostream& o) { o << sweep_csv(rows); });
    nlohmann::json ref = reference.description;
    ref["scene"] = args->scene;
    write_json_file(dir + "/reference.json", ref);
    if (!reference.gathered.empty())
      write_file_atomically(dir + "/reference_samples.json", [&](std::ostream& o) {
        write_reference_samples(o, scene, reference, options.samples_per_patch);
      });
    write_json_file(dir + "/fit.json", fits);
    write_file_atomically(dir + "/command.txt", [&](std::ostream& o) {
      o << fmt::format(
          "build/bin/hrad sweep {} --out {}{}{}", args->scene, dir, args->quick ? " --quick" : "",
          args->reference_elements > 0 ? fmt::format(" --reference-elements {}", args->reference_elements) : "");
      if (!args->reference_from.empty()) o << " --reference-from " << args->reference_from;
      for (const auto& [name, text] : {std::pair{"--elements", args->elements},
                                       {"--patches", args->patches},
                                       {"--feps", args->feps},
                                       {"--aeps", args->aeps}})
        if (!text.empty()) o << " " << name << " " << text;
      if (args->visibility_samples > 0) o << " --visibility-samples " << args->visibility_samples;
      if (args->source_levels != "0") o << " --source-levels " << args->source_levels;
      if (args->no_gather) o << " --no-gather";
      if (args->keep_near_faces) o << " --no-cut-near-faces";
      if (cmd->count("--gather-tolerance")) o << " --gather-tolerance " << args->gather_tolerance;
      if (cmd->count("--gather-sources")) o << " --gather-sources " << args->gather_sources;
      // Every other option given, so that the line reruns exactly this sweep.
      if (cmd->count("--samples")) o << " --samples " << args->samples;
      if (cmd->count("--target-error")) o << " --target-error " << args->target_error;
      if (cmd->count("--feps-aeps")) o << " --feps-aeps " << args->feps_aeps;
      if (cmd->count("--push")) o << " --push " << args->push;
      if (cmd->count("--basis")) o << " --basis " << args->basis;
      if (cmd->count("--threads")) o << " --threads " << args->threads;
      o << "\n";
    });
    run_plot("pareto.py", {dir + "/sweep.csv", dir + "/pareto.png", "What accuracy costs in time: " + scene.path});

    outputs.commit();
    std::cout << fmt::format("{} runs; wrote {}/sweep.csv, reference.json, fit.json, pareto.png\n", rows.size(), dir);
    for (const char* key : {"speedup", "speedup_smooth", "speedup_gathered", "speedup_at_common_error",
                            "speedup_at_common_error_smooth", "speedup_at_common_error_gathered",
                            "speedup_extrapolated", "speedup_extrapolated_smooth", "speedup_extrapolated_gathered"})
      if (fits.contains(key)) std::cout << key << ": " << fits[key].dump() << "\n";
  });
}

}  // namespace hrad::cli
