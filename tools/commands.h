// Each subcommand registers itself on the top-level CLI11 app; see its file for its help text.
#pragma once

#include <CLI/CLI.hpp>

namespace hrad::cli {

void add_info_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_solve_command(CLI::App& app);
void add_formfactor_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_figures_command(CLI::App& app);
void add_scene_command(CLI::App& app);
void add_reference_command(CLI::App& app);
void add_viewfactors_command(CLI::App& app);
void add_probe_command(CLI::App& app);
void add_compare_command(CLI::App& app);

}  // namespace hrad::cli
