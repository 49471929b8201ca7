// hrad: hierarchical radiosity research toolkit, command-line front end.
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include <fmt/format.h>

#include "commands.h"
#include "hrad/core/error.h"
#include "hrad/core/memory.h"
#include "hrad/version.h"

int main(int argc, char** argv) {
  CLI::App app{
      "hrad: radiosity research toolkit (classical, substructuring, hierarchical).\n"
      "Run `hrad SUBCOMMAND --help` for the options of each subcommand."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "hrad " HRAD_VERSION);
  hrad::cli::add_info_command(app);
  hrad::cli::add_render_command(app);
  hrad::cli::add_solve_command(app);
  hrad::cli::add_formfactor_command(app);
  hrad::cli::add_sweep_command(app);
  hrad::cli::add_figures_command(app);
  hrad::cli::add_scene_command(app);
  hrad::cli::add_reference_command(app);
  hrad::cli::add_viewfactors_command(app);
  hrad::cli::add_probe_command(app);
  hrad::cli::add_compare_command(app);
  try {
    // CLI11 reports an unknown first word only as "A subcommand is required": name it instead.
    const auto known_subcommand = [&app](const std::string& name) {
      for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
        if (sub->check_name(name)) return true;
      return false;
    };
    if (argc > 1 && argv[1][0] != '-' && !known_subcommand(argv[1])) {
      std::string known;
      for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
        known += (known.empty() ? "" : ", ") + sub->get_name();
      throw hrad::Error(fmt::format("unknown subcommand '{}' (expected one of: {})", argv[1], known));
    }
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "hrad: error: %s\n", e.what());
    return 2;
  } catch (const hrad::Error& e) {
    std::fprintf(stderr, "hrad: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    // Sizes are checked up front (solvers/work_estimate.h, render, scene generate); this is what slipped by.
    std::string running = "hrad";
    for (const CLI::App* sub : app.get_subcommands()) running = sub->get_name();
    // What was being allocated and the option that makes it smaller, when the work named it.
    if (const std::string failed = hrad::failed_allocation(); !failed.empty()) {
      std::fprintf(stderr, "hrad: error: out of memory in '%s' while allocating %s\n", running.c_str(), failed.c_str());
      return 1;
    }
    std::fprintf(stderr,
                 "hrad: error: out of memory in '%s': make the work smaller (solve: a larger --aeps or --max-area; "
                 "render: a smaller --width/--height; scene generate: fewer --polygons)\n",
                 running.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hrad: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
