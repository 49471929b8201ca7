// Outputs as a user meets them (io/atomic_file.h): an output never replaces an input of the same
// command (links resolved), two outputs are never one file, only a regular file or a new path is
// written, every output's folder is checked before any work, and an interrupted run leaves nothing.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "hrad/core/face_geometry.h"
#include "hrad/io/solution_ply.h"
#include "run_hrad.h"
#include "support/source_tree.h"

namespace hrad::test {
namespace {

namespace fs = std::filesystem;

const std::string kMtl = "newmtl white\nKd 0.5 0.5 0.5\nnewmtl light\nKd 0.5 0.5 0.5\nKe 10 10 10\n";
// Two facing unit squares, the lower one emitting: a solve takes milliseconds.
const std::string kObj =
    "mtllib s.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"
    "usemtl light\nf 1 4 3 2\nusemtl white\nf 5 6 7 8\n";

struct Fixture {
  TempDir dir;
  std::string obj, mtl;
  Fixture() {
    mtl = dir.write("s.mtl", kMtl);
    obj = dir.write("s.obj", kObj);
  }
  std::string d() const { return dir.root().string(); }
};

// The error is one line naming `fragment`, the exit is 1, and the folder holds exactly `entries`.
void expect_refused(const RunResult& r, const std::string& fragment, const TempDir& dir, std::size_t entries) {
  EXPECT_EQ(r.exit_code, 1) << r.err;
  ASSERT_EQ(r.err_lines().size(), 1u) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_EQ(dir.entries(), entries) << "something was written or left behind";
}

TEST(CliOutputs, OutputNamingTheSceneIsRefusedAndTheSceneKept) {
  Fixture f;
  expect_refused(run_hrad("solve " + f.obj + " --out " + f.obj, f.dir), "--out " + f.obj + " is the scene", f.dir, 2);
  EXPECT_EQ(slurp(f.obj), kObj);
  // The material library is an input too (known once the scene is read, still before the solve).
  expect_refused(run_hrad("solve " + f.obj + " --report " + f.mtl, f.dir), "is an input of the scene", f.dir, 2);
  EXPECT_EQ(slurp(f.mtl), kMtl);
}

TEST(CliOutputs, LinksAreResolved) {
  Fixture f;
  fs::create_symlink(f.obj, f.d() + "/link.obj");  // a symbolic link to the scene
  expect_refused(run_hrad("solve " + f.obj + " --out " + f.d() + "/link.obj", f.dir), "is the scene", f.dir, 3);
  fs::create_hard_link(f.mtl, f.d() + "/hard.mtl");  // the same inode under another name
  expect_refused(run_hrad("solve " + f.obj + " --report " + f.d() + "/hard.mtl", f.dir), "is an input", f.dir, 4);
  EXPECT_EQ(slurp(f.obj), kObj);
  EXPECT_EQ(slurp(f.mtl), kMtl);
  // A link to a fresh regular file is written through: the link stays a link, its target gets the report.
  f.dir.write("target.json", "old");
  fs::create_symlink(f.d() + "/target.json", f.d() + "/r.json");
  const RunResult ok = run_hrad("solve " + f.obj + " --quiet --report " + f.d() + "/r.json", f.dir);
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(fs::is_symlink(f.d() + "/r.json"));
  EXPECT_NE(slurp(f.d() + "/target.json").find("\"method\""), std::string::npos);
}

TEST(CliOutputs, TwoOutputsOneFileIsRefused) {
  Fixture f;
  expect_refused(run_hrad("solve " + f.obj + " --out " + f.d() + "/x --report " + f.d() + "/x", f.dir),
                 "the same file for two outputs", f.dir, 2);
  // Not yet existing, spelled differently: the same path once normalised.
  expect_refused(run_hrad("solve " + f.obj + " --out " + f.d() + "/x --report " + f.d() + "/./sub/../x", f.dir),
                 "the same file for two outputs", f.dir, 2);
  // scene generate writes FILE.obj and FILE.mtl beside it: --out x.mtl would make them one file.
  expect_refused(run_hrad("scene generate --polygons 100 --out " + f.d() + "/x.mtl", f.dir),
                 "the same file for two outputs", f.dir, 2);
}

TEST(CliOutputs, RenderNeverReplacesItsSolution) {
  Fixture f;
  ASSERT_EQ(run_hrad("solve " + f.obj + " --quiet --out " + f.d() + "/a.ply", f.dir).exit_code, 0);
  const std::string before = slurp(f.d() + "/a.ply");
  expect_refused(run_hrad("render " + f.d() + "/a.ply --out " + f.d() + "/a.ply", f.dir), "is the solution", f.dir, 3);
  EXPECT_EQ(slurp(f.d() + "/a.ply"), before);
}

TEST(CliOutputs, OnlyRegularFilesOrNewPathsAreWritten) {
  Fixture f;
  fs::create_directory(f.d() + "/folder");
  expect_refused(run_hrad("solve " + f.obj + " --out " + f.d() + "/folder", f.dir), "is a directory", f.dir, 3);
  ASSERT_EQ(mkfifo((f.d() + "/fifo").c_str(), 0644), 0);
  expect_refused(run_hrad("solve " + f.obj + " --report " + f.d() + "/fifo", f.dir), "is a FIFO", f.dir, 4);
  EXPECT_TRUE(fs::is_fifo(f.d() + "/fifo"));  // still a FIFO, not renamed over
  expect_refused(run_hrad("solve " + f.obj + " --report /dev/null", f.dir), "is a character device", f.dir, 4);
}

TEST(CliOutputs, UnwritableFolderIsRefusedBeforeAnyWorkAndLeavesNoReport) {
  Fixture f;
  // /proc takes no new entries, even from root (CI runs as root, so permission bits would not do).
  const RunResult r =
      run_hrad("solve " + f.obj + " --report " + f.d() + "/r.json --out /proc/hrad-no-such/s.ply", f.dir);
  expect_refused(r, "/proc/hrad-no-such/s.ply: cannot write into /proc", f.dir, 2);
  EXPECT_TRUE(r.out.empty()) << "the solve ran: " << r.out;
}

TEST(CliOutputs, RenderRefusesAFifoInsteadOfBlocking) {
  Fixture f;
  ASSERT_EQ(mkfifo((f.d() + "/in.ply").c_str(), 0644), 0);
  const auto start = std::chrono::steady_clock::now();
  // `timeout` turns a hang into exit 124 instead of a stuck test.
  const RunResult r = run_hrad("render " + f.d() + "/in.ply --out " + f.d() + "/i.png", f.dir);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  expect_refused(r, "is a FIFO", f.dir, 3);
}

TEST(CliOutputs, FilesGetTheUmasksModeLikeAnyProgramsOutput) {
  Fixture f;
  for (const auto& [mask, mode] : {std::pair{"022", 0644}, {"027", 0640}}) {
    TempDir out;
    const std::string o = out.root().string();
    const RunResult r =
        run_hrad(std::string("solve ") + f.obj + " --quiet --report " + o + "/r.json --out " + o + "/s.ply", out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // run_hrad's shell inherits this process's umask: set it for the child explicitly instead.
    const RunResult masked = run_hrad(std::string("--version >/dev/null; umask ") + mask + "; '" +
                                          test::hrad_executable() + "' render " + o + "/s.ply --out " + o + "/i.png",
                                      out);
    ASSERT_EQ(masked.exit_code, 0) << masked.err;
    struct stat st {};
    ASSERT_EQ(stat((o + "/i.png").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, static_cast<unsigned>(mode)) << "umask " << mask;
  }
}

// Starts the executable with `args` directly, its output to /dev/null: a shell without job control
// starts background jobs with SIGINT ignored, as a terminal's Ctrl-C never would.
pid_t start_hrad(const std::vector<std::string>& args) {
  std::vector<char*> argv{const_cast<char*>("hrad")};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (std::freopen("/dev/null", "w", stderr) == nullptr || std::freopen("/dev/null", "w", stdout) == nullptr)
      _exit(99);
    execv(test::hrad_executable().c_str(), argv.data());
    _exit(98);
  }
  return pid;
}

// Whether `dir` holds a staging folder, and whether that holds a file (the outputs being written).
std::pair<bool, bool> staging_in(const std::string& dir) {
  std::pair<bool, bool> seen{false, false};
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().filename().string().rfind(".hrad-tmp-", 0) == 0) {
      seen.first = true;
      for (const auto& f : fs::directory_iterator(e.path(), ec)) seen.second |= f.is_regular_file(ec);
    }
  return seen;
}

// Sends `sig` to `pid` and expects it to die of it (as without the handler).
void interrupt(pid_t pid, int sig) {
  kill(pid, sig);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit " << (WIFEXITED(status) ? WEXITSTATUS(status) : -1);
  EXPECT_EQ(WTERMSIG(status), sig);
}

// A signal in the middle of a solve: the staging folder made at the start is removed and the process
// dies of the signal, leaving only the inputs.
TEST(CliOutputs, InterruptedSolveLeavesNothing) {
  TempDir dir;
  const std::string d = dir.root().string();
  ASSERT_EQ(run_hrad("scene generate --polygons 400 --out " + d + "/g.obj", dir).exit_code, 0);
  for (const int sig : {SIGINT, SIGTERM}) {
    // ~12k elements: minutes of form factors, interrupted long before the outputs are written.
    const pid_t pid = start_hrad({"solve", d + "/g.obj", "--method", "full", "--max-area", "0.05", "--report",
                                  d + "/r.json", "--out", d + "/s.ply"});
    ASSERT_GT(pid, 0);
    bool staging_seen = false;
    for (int i = 0; i < 200 && !staging_seen; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      staging_seen = staging_in(d).first;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // into the form factors
    interrupt(pid, sig);
    EXPECT_TRUE(staging_seen) << "no staging folder while running";
    EXPECT_EQ(dir.entries(), 2u) << "left behind after signal " << sig;
  }
}

// A signal while the outputs are being written (files in the staging folder, growing: 300k generated
// polygons are ~50 MB of OBJ): the half-written files go with their folder, nothing reaches --out.
TEST(CliOutputs, InterruptedWriteLeavesNothing) {
  TempDir dir;
  const std::string d = dir.root().string();
  for (const int sig : {SIGINT, SIGTERM}) {
    const pid_t pid = start_hrad({"scene", "generate", "--polygons", "300000", "--out", d + "/g.obj"});
    ASSERT_GT(pid, 0);
    bool writing = false;
    for (int i = 0; i < 4000 && !writing; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      writing = staging_in(d).second;
    }
    interrupt(pid, sig);
    EXPECT_TRUE(writing) << "never caught the outputs being written";
    EXPECT_EQ(dir.entries(), 0u) << "left behind after signal " << sig;
  }
}

// A 1e-6 x 1e-6 light 1 km from the origin in a 1 km room: the PLY (double positions) keeps it.
TEST(CliOutputs, TinyPatchInAHugeRoomSurvivesThePly) {
  TempDir dir;
  const std::string d = dir.root().string();
  dir.write("room.mtl", "newmtl wall\nKd 0.5 0.5 0.5\nnewmtl light\nKd 0 0 0\nKe 1 1 1\n");
  // The cube [0, 1000]^3 facing inwards, and the light just below the ceiling's corner, facing down.
  dir.write(
      "room.obj",
      "mtllib room.mtl\nusemtl wall\n"
      "v 0 0 0\nv 1000 0 0\nv 1000 0 1000\nv 0 0 1000\nv 0 1000 0\nv 1000 1000 0\nv 1000 1000 1000\nv 0 1000 1000\n"
      "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n"
      "usemtl light\nv 999.999998 999.999 999.999998\nv 999.999999 999.999 999.999998\n"
      "v 999.999999 999.999 999.999999\nv 999.999998 999.999 999.999999\nf 9 10 11 12\n");
  const RunResult r = run_hrad("solve " + d + "/room.obj --quiet --method full --out " + d + "/s.ply", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Solution s = read_solution_ply(d + "/s.ply");
  double light_area = 0.0;
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    if (s.face_patch[f] == 6) light_area += face_area(s, f);
  EXPECT_NEAR(light_area, 1e-12, 1e-6 * 1e-12);  // printed corners 1e-6 apart: area 1e-12 to double rounding
}

}  // namespace
}  // namespace hrad::test

namespace hrad::test {
namespace {

// `hrad figures` from a folder other than the repository root finds the bundled scenes beside the
// executable's source tree and its plot scripts beside the executable; the plot's PNG gets the
// umask's mode like every other output (matplotlib's mkstemp made it 0600).
TEST(CliOutputs, FiguresRunFromAnyFolderAndPlotsGetTheUmasksMode) {
  TempDir dir;
  const std::string d = dir.root().string();
  const RunResult r = run_hrad("--version >/dev/null; cd " + d + " && umask 022 && '" + test::hrad_executable() +
                                   "' figures --out figs --quick --only 3",
                               dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  struct stat st {};
  ASSERT_EQ(stat((d + "/figs/fig3_far.png").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0644u);
  ASSERT_EQ(stat((d + "/figs/fig3_far.csv").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0644u);
  for (const auto& e : fs::directory_iterator(d + "/figs"))
    EXPECT_EQ(e.path().filename().string().find(".hrad-tmp"), std::string::npos) << "staging left behind";
}

}  // namespace
}  // namespace hrad::test
