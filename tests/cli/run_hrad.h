// Runs the `hrad` executable in a shell with stdout and stderr captured to files.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../support/source_tree.h"
#include "../support/temp_dir.h"

namespace hrad::test {

struct RunResult {
  int exit_code = -1;  ///< the process's exit status; 128 + signal when it was killed
  std::string out, err;
  /// stderr split into lines (no empty trailing line).
  std::vector<std::string> err_lines() const {
    std::vector<std::string> lines;
    std::istringstream in(err);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The comma-separated cells of one CSV line (for outputs whose cells hold no commas); a line
/// ending in a comma ends in an empty cell.
inline std::vector<std::string> csv_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

/// Runs `hrad args` (args are passed to /bin/sh as written) with the source tree as
/// working directory; the captured streams go to files in `scratch`.
inline RunResult run_hrad(const std::string& args, const TempDir& scratch) {
  const std::string out = scratch.path(".stdout"), err = scratch.path(".stderr");
  const std::string command =
      "cd '" + source_dir() + "' && '" + hrad_executable() + "' " + args + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(command.c_str());
  RunResult r;
  if (WIFEXITED(status))
    r.exit_code = WEXITSTATUS(status);
  else if (WIFSIGNALED(status))
    r.exit_code = 128 + WTERMSIG(status);
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

}  // namespace hrad::test
