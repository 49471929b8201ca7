#include "hrad/io/atomic_file.h"

#include <filesystem>
#include <fstream>
#include <random>

#include <fmt/format.h>

#include "hrad/core/error.h"

namespace hrad {
namespace {

std::string temporary_name(const std::string& path) {
  static thread_local std::mt19937_64 rng(std::random_device{}());
  return fmt::format("{}.tmp-{:08x}", path, static_cast<unsigned>(rng()));
}

}  // namespace

void write_path_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty() && !fs::is_directory(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec) throw Error(fmt::format("{}: cannot create folder: {}", parent.string(), ec.message()));
  }
  const std::string tmp = temporary_name(path);
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw Error(fmt::format("{}: cannot write: {}", path, ec.message()));
  }
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write, bool binary) {
  write_path_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp, binary ? std::ios::binary : std::ios::out);
    if (!out) throw Error(fmt::format("{}: cannot open for writing", path));
    write(out);
    out.flush();
    if (!out) throw Error(fmt::format("{}: write failed", path));
  });
}

}  // namespace hrad
