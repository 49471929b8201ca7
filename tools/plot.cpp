#include "plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <cstdlib>
#include <filesystem>
#include <utility>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/io/atomic_file.h"

extern char** environ;

namespace hrad::cli {

namespace {

std::string plot_python() {
  const char* env_python = std::getenv("HRAD_PYTHON");
  return env_python ? env_python : "/usr/bin/python3";
}

// Starts `argv` (argv[0] is the program); false when it cannot be started. `quiet`: its output goes
// to /dev/null.
bool spawn(std::vector<std::string> argv_s, bool quiet, pid_t* pid) {
  std::vector<char*> argv;
  for (std::string& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (quiet) {
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  }
  const bool spawned = posix_spawn(pid, argv[0], &actions, nullptr, argv.data(), environ) == 0;
  posix_spawn_file_actions_destroy(&actions);
  return spawned;
}

}  // namespace

void require_plotting() {
  const std::string python = plot_python();
  pid_t pid = 0;
  int status = 0;
  const bool spawned = spawn({python, "-c", "import matplotlib"}, true, &pid);
  if (spawned) waitpid(pid, &status, 0);
  if (!spawned || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(
        fmt::format("{}: cannot import matplotlib, which the plots need: install it with "
                    "scripts/install_deps.sh (Debian's python3-matplotlib)",
                    python));
}

void run_plot(const std::string& script, const std::vector<std::string>& args) {
  namespace fs = std::filesystem;
  const fs::path exe = fs::read_symlink("/proc/self/exe");
  const std::string path = (exe.parent_path() / "plots" / script).string();
  if (!fs::is_regular_file(path)) throw Error(fmt::format("{}: plot script missing (rebuild hrad)", path));
  const std::string python = plot_python();
  // Files this command writes are staged until its end (io/atomic_file.h): the script reads and
  // writes the staged temporaries, which the signal handler removes (and kills the script first).
  std::vector<std::string> argv_s = {python, path};
  for (const std::string& a : args) argv_s.push_back(staged_path(a));
  pid_t pid = 0;
  if (!spawn(std::move(argv_s), false, &pid))
    throw Error(
        fmt::format("{}: cannot run (plots need Debian's python3 with matplotlib: scripts/install_deps.sh)", python));
  set_output_child(pid);
  int status = 0;
  waitpid(pid, &status, 0);
  set_output_child(0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(fmt::format("plot script {} failed (exit {})", script, WIFEXITED(status) ? WEXITSTATUS(status) : -1));
}

}  // namespace hrad::cli
