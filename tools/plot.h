// Plots are drawn by matplotlib scripts (tools/plots/*.py, copied beside the hrad binary at build
// time) run with Debian's /usr/bin/python3; each writes its PNG atomically.
#pragma once

#include <string>
#include <vector>

namespace hrad::cli {

/// Runs plots/`script` (beside the executable) with `args`; hrad::Error when it fails.
void run_plot(const std::string& script, const std::vector<std::string>& args);

}  // namespace hrad::cli
