#include "hrad/io/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/io/input_file.h"

namespace hrad {
namespace fs = std::filesystem;
namespace {

// --- Temporaries the signal handler removes ------------------------------------------------------
// Fixed storage, so that the handler touches nothing but these arrays and async-signal-safe calls
// (unlink, rmdir, kill, waitpid: POSIX.1-2008 sec. 2.4.3). A path that does not fit is still removed
// by the destructor, only not on a signal.
constexpr int kSlots = 256;
constexpr std::size_t kPathMax = 4096;
enum SlotKind : int { kFree = 0, kFilling = 1, kFile = 2, kFolder = 3 };
struct Slot {
  std::atomic<int> kind{kFree};
  char path[kPathMax];
};
Slot g_slots[kSlots];
std::atomic<pid_t> g_child{0};
std::atomic<OutputFiles*> g_active{nullptr};

extern "C" void remove_temporaries_and_die(int sig) {
  const pid_t child = g_child.load();
  if (child > 0) {
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
  }
  for (Slot& s : g_slots)
    if (s.kind.load() == kFile) unlink(s.path);
  // Folders nest (a staging folder holds the folders made inside it): remove until nothing more goes.
  for (int pass = 0; pass < 16; ++pass) {
    bool removed = false;
    for (Slot& s : g_slots)
      if (s.kind.load() == kFolder && rmdir(s.path) == 0) {
        s.kind.store(kFree);
        removed = true;
      }
    if (!removed) break;
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void install_handler_once() {
  static const bool installed = [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;  // keep a caller's handler
      struct sigaction action {};
      action.sa_handler = remove_temporaries_and_die;
      sigemptyset(&action.sa_mask);
      sigaction(sig, &action, nullptr);
    }
    return true;
  }();
  (void)installed;
}

int register_path(const std::string& path, SlotKind kind) {
  if (path.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (g_slots[i].kind.compare_exchange_strong(expected, kFilling)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      g_slots[i].kind.store(kind);
      return i;
    }
  }
  return -1;
}

void unregister_path(const std::string& path) {
  for (Slot& s : g_slots) {
    const int kind = s.kind.load();
    if ((kind == kFile || kind == kFolder) && path == s.path) s.kind.store(kFree);
  }
}

// --- What a path names ------------------------------------------------------------------------------

/// The file a path names: device and inode when it exists (links followed), else its canonical path.
struct Identity {
  bool exists = false;
  dev_t dev = 0;
  ino_t ino = 0;
  std::string canonical;
  bool operator==(const Identity& o) const {
    return exists && o.exists ? dev == o.dev && ino == o.ino : canonical == o.canonical;
  }
};

std::string canonical_of(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path).lexically_normal().string() : p.string();
}

Identity identity_of(const std::string& path) {
  Identity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.dev = st.st_dev;
    id.ino = st.st_ino;
  }
  id.canonical = canonical_of(path);
  return id;
}

/// The nearest existing folder at or above `folder`; hrad::Error when something above is not a folder.
std::string existing_ancestor(const std::string& describe, fs::path folder) {
  std::error_code ec;
  while (true) {
    if (fs::exists(folder, ec)) {
      if (!fs::is_directory(folder, ec)) throw Error(fmt::format("{}: {} is not a folder", describe, folder.string()));
      return folder.string();
    }
    if (!folder.has_parent_path() || folder.parent_path() == folder) return folder.string();
    folder = folder.parent_path();
  }
}

bool is_under(const std::string& path, const std::string& folder) {
  return path.size() > folder.size() && path.compare(0, folder.size(), folder) == 0 &&
         (folder.back() == '/' || path[folder.size()] == '/');
}

std::string describe(const std::string& option, const std::string& path) {
  return option.empty() ? path : option + " " + path;
}

// Files are made with open(2) and mode 0666, so the umask alone decides their permissions (mkstemp
// would make them 0600).
void make_empty_file(const std::string& path, const std::string& shown) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw Error(fmt::format("{}: cannot write: {}", shown, std::strerror(errno)));
  ::close(fd);
}

}  // namespace

// --- OutputFiles ------------------------------------------------------------------------------------

OutputFiles::OutputFiles() {
  install_handler_once();
  previous_ = g_active.exchange(this);
}

OutputFiles::~OutputFiles() {
  g_active.store(previous_);
  if (committed_) return;
  std::error_code ec;
  for (const auto& [tmp, target] : staged_) {
    fs::remove(tmp, ec);
    unregister_path(tmp);
  }
  for (const auto& [ancestor, staging] : staging_) {
    fs::remove_all(staging, ec);
    unregister_path(staging);
  }
  for (const std::string& f : made_folders_) unregister_path(f);
}

std::string OutputFiles::staging_for(const std::string& ancestor) {
  if (const auto it = staging_.find(ancestor); it != staging_.end()) return it->second;
  std::string pattern = (fs::path(ancestor) / ".hrad-tmp-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw Error(fmt::format("cannot write into {}: {}", ancestor, std::strerror(errno)));
  // mkdtemp makes it 0700; the files inside get their own modes, the folder goes at commit.
  register_path(pattern, kFolder);
  staging_[ancestor] = pattern;
  return pattern;
}

void OutputFiles::declare(const std::string& option, const std::string& path) {
  const std::string shown = describe(option, path);
  if (path.empty()) throw Error(fmt::format("{}: empty file name", option.empty() ? "output" : option));
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw Error(fmt::format("{}: {}", shown, file_kind(st.st_mode)));
  if (!path.empty() && path.back() == '/') throw Error(fmt::format("{}: names a folder, not a file", shown));
  Output out{option, path, canonical_of(path), false};
  const Identity id = identity_of(path);
  for (const Output& o : outputs_)
    if (!o.folder && identity_of(o.path) == id)
      throw Error(fmt::format("{} and {}: the same file for two outputs", describe(o.option, o.path), shown));
  try {
    staging_for(existing_ancestor(shown, fs::path(out.target).parent_path()));
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", shown, e.what()));
  }
  outputs_.push_back(std::move(out));
}

void OutputFiles::declare_folder(const std::string& option, const std::string& path) {
  const std::string shown = describe(option, path);
  if (path.empty()) throw Error(fmt::format("{}: empty folder name", option.empty() ? "output" : option));
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
    throw Error(fmt::format("{}: is a file, not a folder", shown));
  Output out{option, path, canonical_of(path), true};
  try {
    staging_for(existing_ancestor(shown, fs::path(out.target)));
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", shown, e.what()));
  }
  outputs_.push_back(std::move(out));
}

void OutputFiles::check_inputs(const std::vector<std::pair<std::string, std::string>>& inputs) const {
  for (const auto& [what, input] : inputs) {
    if (input.empty()) continue;
    const Identity in = identity_of(input);
    for (const Output& o : outputs_)
      if (!o.folder && identity_of(o.path) == in)
        throw Error(
            fmt::format("{} is {} ({}): an output never replaces an input", describe(o.option, o.path), what, input));
  }
}

std::string OutputFiles::temporary_for(const std::string& path) {
  const std::string target = canonical_of(path);
  const Output* covering = nullptr;
  for (const Output& o : outputs_)
    if ((!o.folder && o.target == target) || (o.folder && is_under(target, o.target))) {
      covering = &o;
      break;
    }
  if (covering == nullptr) return "";
  for (const auto& [tmp, t] : staged_)
    if (t == target) return tmp;  // written again: the same temporary
  const std::string ancestor =
      existing_ancestor(path, covering->folder ? fs::path(covering->target) : fs::path(target).parent_path());
  const fs::path tmp = fs::path(staging_for(ancestor)) / fs::path(target).lexically_relative(ancestor);
  // Folders between the staging folder and the file, outermost first, registered for removal.
  std::vector<fs::path> missing;
  for (fs::path f = tmp.parent_path(); !fs::exists(f); f = f.parent_path()) missing.push_back(f);
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    std::error_code ec;
    fs::create_directory(*it, ec);
    if (ec) throw Error(fmt::format("{}: cannot write: {}", path, ec.message()));
    register_path(it->string(), kFolder);
    made_folders_.push_back(it->string());
  }
  register_path(tmp.string(), kFile);
  staged_.emplace_back(tmp.string(), target);
  return tmp.string();
}

void OutputFiles::commit() {
  for (const auto& [tmp, target] : staged_) {
    std::error_code ec;
    if (!fs::exists(tmp, ec)) continue;  // declared, never written
    fs::create_directories(fs::path(target).parent_path(), ec);
    if (ec)
      throw Error(fmt::format("{}: cannot create folder: {}", fs::path(target).parent_path().string(), ec.message()));
    fs::rename(tmp, target, ec);
    if (ec) throw Error(fmt::format("{}: cannot write: {}", target, ec.message()));
    unregister_path(tmp);
  }
  std::error_code ec;
  for (const auto& [ancestor, staging] : staging_) {
    fs::remove_all(staging, ec);
    unregister_path(staging);
  }
  for (const std::string& f : made_folders_) unregister_path(f);
  committed_ = true;
}

// --- The writers every module uses ------------------------------------------------------------------

void write_path_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  OutputFiles* active = g_active.load();
  std::string tmp = active ? active->temporary_for(path) : "";
  if (!tmp.empty()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    make_empty_file(tmp, path);
    write(tmp);
    return;  // renamed by the active OutputFiles' commit()
  }
  OutputFiles own;
  own.declare("", path);
  tmp = own.temporary_for(path);
  make_empty_file(tmp, path);
  write(tmp);
  own.commit();
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write, bool binary) {
  write_path_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, binary ? std::ios::binary | std::ios::trunc : std::ios::out | std::ios::trunc);
    if (!out) throw Error(fmt::format("{}: cannot open for writing", path));
    write(out);
    out.flush();
    if (!out) throw Error(fmt::format("{}: write failed", path));
  });
}

std::string staged_path(const std::string& path) {
  OutputFiles* active = g_active.load();
  if (active == nullptr) return path;
  // Only files already staged: a path that is not an output is returned as it is.
  const std::string tmp = active->temporary_for(path);
  return tmp.empty() ? path : tmp;
}

void set_output_child(pid_t pid) { g_child.store(pid); }

}  // namespace hrad
