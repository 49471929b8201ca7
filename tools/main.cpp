// hrad: hierarchical radiosity research toolkit, command-line front end.
#include <cstdio>
#include <exception>

#include <fmt/format.h>

#include "commands.h"
#include "hrad/core/error.h"

int main(int argc, char** argv) {
  CLI::App app{
      "hrad: radiosity research toolkit (classical, substructuring, hierarchical).\n"
      "Run `hrad SUBCOMMAND --help` for the options of each subcommand."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "hrad 0.1.0");
  hrad::cli::add_info_command(app);
  hrad::cli::add_render_command(app);
  hrad::cli::add_solve_command(app);
  hrad::cli::add_formfactor_command(app);
  hrad::cli::add_sweep_command(app);
  hrad::cli::add_figures_command(app);
  try {
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
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hrad: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
