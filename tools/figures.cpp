// hrad figures --out DIR [--quick] [--scenes DIR] [--only LIST] [--threads N]
//
// The lecture's figures (Lischinski, "Hierarchical Radiosity"), measured. Each figure N is written as
// DIR/figN_<name>.png with the CSV behind it, DIR/figN_<name>.csv:
//   fig1_cost         form factors (links) against elements on the Cornell box: full n^2,
//                     substructuring nN, hierarchical links (aeps varied at fixed feps); log-log
//                     with the n^2 and n lines; fits in fig1_cost_fit.json
//   fig2_edge         two surfaces meeting along an edge (two_surfaces_edge.obj): the hierarchical
//                     element mesh (fig2_edge_mesh.png, links drawn when the solver records them)
//                     and element size against distance to the common edge
//   fig3_far          two surfaces far apart (two_far_surfaces.obj), k elements per surface: the
//                     full matrix's k^2 pairs, substructuring's 2k factors, HR's links at the same
//                     finest element size
//   fig4_nbody        Barnes-Hut interactions per body against n for several theta, and n - 1
//   fig5_convergence  relative change per iteration (the stopping measure) on the Cornell box: full (Jacobi),
//                     substructuring, hierarchical
//   fig6_equal_time   the Cornell box by each method at about the hierarchical solve's time, with
//                     false-colour error images against a finer full-matrix LU reference
//                     (fig6_<method>.png, fig6_<method>_error.png, montage fig6_equal_time.png)
// plus DIR/headlines.json (the numbers the README quotes) and DIR/command.txt. Progress on stderr.
//   --quick          small settings (for tests; well under a minute)
//   --scenes DIR     where cornell_box.obj, two_surfaces_edge.obj, two_far_surfaces.obj are
//                    (default notebooks_data/scenes)
//   --only LIST      comma-separated figure numbers, e.g. 1,3 (default all)
#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "commands.h"
#include "hrad/core/error.h"
#include "hrad/core/tone_map.h"
#include "hrad/experiments/figures.h"
#include "hrad/io/atomic_file.h"
#include "hrad/io/png_writer.h"
#include "hrad/io/scene_reader.h"
#include "hrad/render/render.h"
#include "hrad/report/report_json.h"
#include "plot.h"

namespace hrad::cli {
namespace {

std::set<int> parse_only(const std::string& text) {
  std::set<int> only;
  if (text.empty()) return {1, 2, 3, 4, 5, 6};
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    int n = 0;
    try {
      std::size_t used = 0;
      n = std::stoi(item, &used);
      if (used != item.size()) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      throw Error(fmt::format("--only: expected figure numbers 1..6 separated by commas, got '{}'", text));
    }
    if (n < 1 || n > 6) throw Error(fmt::format("--only: figure {} does not exist (1..6)", n));
    only.insert(n);
  }
  return only;
}

Scene load(const std::string& path) {
  std::vector<std::string> warnings;
  Scene scene = read_scene(path, &warnings);
  for (const auto& w : warnings) std::cerr << w << "\n";
  return scene;
}

void write_text(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](std::ostream& o) { o << text; });
}

// A view of two surfaces meeting along an edge from the side both fronts face.
Camera edge_camera(const Solution& s, int width, int height) {
  const auto [lo, hi] = solution_bounds(s);
  const Vec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * (hi - lo).norm();
  Camera c;
  c.target = centre;
  c.position = centre + 2.6 * radius * Vec3(0.55, 0.6, 0.8).normalized();
  c.up = Vec3::UnitY();
  c.vfov_deg = 40.0;
  c.width = width;
  c.height = height;
  return c;
}

// Writes the seconds of its scope into (*out)[name] when it ends.
class Lap {
 public:
  Lap(nlohmann::json* out, std::string name) : out_(out), name_(std::move(name)) {}
  ~Lap() { (*out_)[name_] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  Lap(const Lap&) = delete;
  Lap& operator=(const Lap&) = delete;

 private:
  nlohmann::json* out_;
  std::string name_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace

void add_figures_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("figures", "The lecture's figures, measured: PNG plots with the CSV behind each");
  struct Args {
    std::string out, scenes = "notebooks_data/scenes", only;
    bool quick = false;
    int threads = 0;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--out", args->out, "Output folder")->required();
  cmd->add_flag("--quick", args->quick, "Small, fast settings (for tests)");
  cmd->add_option("--scenes", args->scenes, "Folder of the bundled scenes (default notebooks_data/scenes)");
  cmd->add_option("--only", args->only, "Comma-separated figure numbers (default: all six)");
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)");
  cmd->callback([args, cmd] {
    const std::set<int> only = parse_only(args->only);
    // Without --scenes: the bundled scenes from the current folder (the repository root), else from
    // the source tree the executable was built in (build/bin/hrad -> notebooks_data/scenes), so that
    // `hrad figures` works from any folder.
    if (cmd->count("--scenes") == 0 && !std::filesystem::is_directory(args->scenes)) {
      const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe");
      const std::filesystem::path beside = exe.parent_path().parent_path().parent_path() / "notebooks_data" / "scenes";
      if (!std::filesystem::is_directory(beside))
        throw Error(
            fmt::format("--scenes: the bundled scenes are neither in ./notebooks_data/scenes nor in {}: give "
                        "--scenes DIR",
                        beside.string()));
      args->scenes = beside.string();
    }
    if (args->threads < 0) throw Error(fmt::format("--threads must be >= 0, got {}", args->threads));
    require_plotting();  // after the option checks, before any work: every figure ends in a plot
    const std::string dir = args->out;
    // Every file goes into a staging folder and is renamed into DIR at the end (io/atomic_file.h).
    OutputFiles outputs;
    outputs.declare_folder("--out", dir);
    const bool quick = args->quick;
    const int threads = args->threads;
    const auto started = std::chrono::steady_clock::now();
    const ProgressFn progress = [](std::string_view line) { std::cerr << "figures: " << line << "\n"; };
    const auto scene_path = [&](const char* name) { return (std::filesystem::path(args->scenes) / name).string(); };
    // Every scene the chosen figures need is read before any work, so a missing one fails fast.
    std::map<std::string, Scene> scenes;
    const auto need = [&](int figure, const char* name) {
      if (only.count(figure) && !scenes.count(name)) scenes.emplace(name, load(scene_path(name)));
    };
    for (int figure : {1, 5, 6}) need(figure, "cornell_box.obj");
    need(2, "two_surfaces_edge.obj");
    need(3, "two_far_surfaces.obj");
    nlohmann::json headlines, figure_seconds;
    headlines["quick"] = quick;

    if (only.count(1)) {
      const Lap lap(&figure_seconds, "fig1");
      const Scene& scene = scenes.at("cornell_box.obj");
      CostOptions o;
      o.threads = threads;
      if (quick) {
        o.element_counts = {8, 16, 32};
        o.substructure_counts = {8, 16, 32, 64};
        o.aeps_fractions = {3e-2, 1e-2, 5e-3};
      }
      const auto rows = cost_rows(scene, o, progress);
      write_text(dir + "/fig1_cost.csv", cost_csv(rows));
      const nlohmann::json fits = cost_fits(rows);
      write_json_file(dir + "/fig1_cost_fit.json", fits);
      run_plot("fig_cost.py", {dir + "/fig1_cost.csv", dir + "/fig1_cost.png", dir + "/fig1_cost_fit.json"});
      for (const auto& [method, measures] : fits["methods"].items())
        for (const auto& [measure, fit] : measures.items())
          if (!fit.is_null())
            headlines["fig1_slope"][method][measure] = {{"b", fit["b"]}, {"b_stderr", fit["b_stderr"]}};
    }

    if (only.count(2)) {
      const Lap lap(&figure_seconds, "fig2");
      const Scene& scene = scenes.at("two_surfaces_edge.obj");
      SolveOptions o;
      o.threads = threads;
      // A coarse form-factor tolerance shows the grading: an element at distance d from the edge links to
      // elements of size ~ sqrt(feps pi) d, so sizes grow in proportion to d down to aeps.
      o.feps = 0.05;
      o.aeps = scene.total_area() * (quick ? 1e-3 : 1e-4);
      o.record_links = true;
      progress(fmt::format("figure 2: hierarchical on {} (aeps {:.3g})", scene.path, o.aeps));
      const EdgeFigure fig = edge_figure(scene, o);
      write_text(dir + "/fig2_edge.csv", edge_csv(fig));
      RenderOptions render;
      render.camera = edge_camera(fig.solution, quick ? 384 : 768, quick ? 384 : 768);
      render.exposure = auto_exposure(fig.solution);
      render.cull_back_faces = false;
      render.background = {255, 255, 255};
      WireframeOptions wire;
      wire.links = fig.solution.link_segments;
      write_png(dir + "/fig2_edge_mesh.png", render_wireframe(fig.solution, render, wire));
      run_plot("fig_edge.py", {dir + "/fig2_edge.csv", dir + "/fig2_edge.png", dir + "/fig2_edge_mesh.png",
                               fmt::format("{} elements, {} links{}", fig.summary.elements, fig.summary.links,
                                           fig.solution.link_segments.empty() ? " (links not recorded)" : "")});
      headlines["fig2"] = {{"elements", fig.summary.elements},
                           {"links", fig.summary.links},
                           {"aeps", o.aeps},
                           {"links_drawn", !fig.solution.link_segments.empty()}};
    }

    if (only.count(3)) {
      const Lap lap(&figure_seconds, "fig3");
      const Scene& scene = scenes.at("two_far_surfaces.obj");
      const std::vector<int> ks = quick ? std::vector<int>{1, 4, 16, 64} : std::vector<int>{1, 4, 16, 64, 256, 1024};
      const auto rows = far_rows(scene, ks, 0.0, threads, progress);
      write_text(dir + "/fig3_far.csv", far_csv(rows));
      run_plot("fig_far.py", {dir + "/fig3_far.csv", dir + "/fig3_far.png"});
      for (const FarRow& r : rows)
        if (r.k == ks.back())
          headlines["fig3_at_largest_k"][r.method] = {
              {"k", r.k}, {"cross_pairs", r.cross_pairs}, {"cross_factors", r.cross_factors}};
    }

    if (only.count(4)) {
      const Lap lap(&figure_seconds, "fig4");
      const std::vector<int> ns =
          quick ? std::vector<int>{64, 256, 1024} : std::vector<int>{100, 300, 1000, 3000, 10000, 20000};
      const std::vector<double> thetas =
          quick ? std::vector<double>{0.0, 0.5, 1.0} : std::vector<double>{0.0, 0.3, 0.5, 0.7, 1.0};
      progress("figure 4: Barnes-Hut");
      const auto samples = barnes_hut_sweep(ns, thetas, 1, quick ? 1024 : 3000);
      write_text(dir + "/fig4_nbody.csv", barnes_hut_csv(samples));
      run_plot("fig_nbody.py", {dir + "/fig4_nbody.csv", dir + "/fig4_nbody.png"});
      for (const BarnesHutSample& s : samples)
        if (s.n == ns.back())
          headlines["fig4_at_largest_n"][fmt::format("theta={:g}", s.theta)] = {
              {"n", s.n}, {"mean_interactions", s.mean_interactions}, {"relative_force_error", s.relative_force_error}};
    }

    if (only.count(5)) {
      const Lap lap(&figure_seconds, "fig5");
      const Scene& scene = scenes.at("cornell_box.obj");
      const auto runs = convergence_runs(scene, quick ? 32 : 128, 1e-6, threads, progress);
      write_text(dir + "/fig5_convergence.csv", convergence_csv(runs));
      run_plot("fig_convergence.py", {dir + "/fig5_convergence.csv", dir + "/fig5_convergence.png"});
      for (const auto& r : runs)
        headlines["fig5_iterations"][r.method] = {{"iterations", r.summary.iterations},
                                                  {"termination", std::string(to_string(r.summary.termination))},
                                                  {"elements", r.summary.elements}};
    }

    if (only.count(6)) {
      const Lap lap(&figure_seconds, "fig6");
      const Scene& scene = scenes.at("cornell_box.obj");
      EqualTimeOptions o;
      o.threads = threads;
      o.reference_elements = quick ? 256 : 2048;  // finer than every equal-time run (4307 / 542 elements)
      o.first_elements = quick ? 16 : 64;
      o.calibration_runs = quick ? 2 : 3;
      if (quick) o.hierarchical.aeps = scene.total_area() * 3e-2;
      const EqualTimeFigure fig = equal_time_figure(scene, o, progress);
      const int size = quick ? 160 : 384;
      const EqualTimeImages images = equal_time_images(scene, fig, size, size);
      for (std::size_t i = 0; i < fig.runs.size(); ++i) {
        write_png(fmt::format("{}/fig6_{}.png", dir, fig.runs[i].method), images.renders[i]);
        write_png(fmt::format("{}/fig6_{}_error.png", dir, fig.runs[i].method), images.errors[i]);
      }
      write_text(dir + "/fig6_equal_time.csv", equal_time_csv(fig));
      run_plot("fig_equal_time.py",
               {dir + "/fig6_equal_time.csv", dir + "/fig6_equal_time.png", fmt::format("{:.3g}", images.error_hi)});
      headlines["fig6_budget_seconds"] = fig.budget_seconds;
      headlines["fig6_reference"] = {{"elements", fig.reference_summary.elements},
                                     {"seconds", fig.reference_summary.total_seconds}};
      for (const auto& r : fig.runs)
        headlines["fig6"][r.method] = {{"elements", r.summary.elements},
                                       {"seconds", r.summary.total_seconds},
                                       {"error_l2", r.error.relative_l2},
                                       {"error_linf", r.error.relative_linf}};
    }

    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    headlines["seconds"] = seconds;
    if (!args->only.empty()) headlines["only"] = args->only;
    for (const auto& [figure, seconds] : figure_seconds.items()) headlines["figure_seconds"][figure] = seconds;
    write_json_file(dir + "/headlines.json", headlines);
    write_text(dir + "/command.txt",
               fmt::format("build/bin/hrad figures --out {}{}{}{}\n", dir, quick ? " --quick" : "",
                           args->scenes != "notebooks_data/scenes" ? " --scenes " + args->scenes : "",
                           args->only.empty() ? "" : " --only " + args->only));
    outputs.commit();
    std::cout << headlines.dump(2) << "\n";
    std::cout << fmt::format("wrote the figures to {} in {:.1f} s\n", dir, seconds);
  });
}

}  // namespace hrad::cli
