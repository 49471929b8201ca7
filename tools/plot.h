// Plots are drawn by matplotlib scripts (tools/plots/*.py, copied beside the hrad binary at build
// time) run with Debian's /usr/bin/python3; each writes its PNG atomically.
#pragma once

#include <string>
#include <vector>

namespace hrad::cli {

/// Runs plots/`script` (beside the executable) with `args`; hrad::Error when it fails.
void run_plot(const std::string& script, const std::vector<std::string>& args);
/// hrad::Error unless the plots' Python can import matplotlib: called before long work that ends in
/// plots (scripts/run.sh installs only what the solves and pictures need).
void require_plotting();

}  // namespace hrad::cli
