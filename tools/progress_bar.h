// A progress bar on stderr for long subcommands: redrawn in place on a terminal, one line per
// step otherwise (logs, CI).
#pragma once

#include <string_view>

namespace hrad::cli {

/// Draws "[#####.....]  5/10  what" on stderr.
void show_progress(int done, int total, std::string_view what);

/// Prints one line on stderr, over the bar on a terminal (the next show_progress() draws it again).
void show_line(std::string_view line);

}  // namespace hrad::cli
