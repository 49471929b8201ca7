#include "plot.h"

#include <spawn.h>
#include <sys/wait.h>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/io/atomic_file.h"

extern char** environ;

namespace hrad::cli {

void run_plot(const std::string& script, const std::vector<std::string>& args) {
  namespace fs = std::filesystem;
  const fs::path exe = fs::read_symlink("/proc/self/exe");
  const std::string path = (exe.parent_path() / "plots" / script).string();
  if (!fs::is_regular_file(path)) throw Error(fmt::format("{}: plot script missing (rebuild hrad)", path));
  const char* env_python = std::getenv("HRAD_PYTHON");
  const std::string python = env_python ? env_python : "/usr/bin/python3";
  // Files this command writes are staged until its end (io/atomic_file.h): the script reads and
  // writes the staged temporaries, which the signal handler removes (and kills the script first).
  std::vector<std::string> argv_s = {python, path};
  for (const std::string& a : args) argv_s.push_back(staged_path(a));
  std::vector<char*> argv;
  for (std::string& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ) != 0)
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
