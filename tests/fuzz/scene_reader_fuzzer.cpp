// Fuzzes the OBJ + MTL reader: any bytes give a Scene or an hrad::Error, never a crash, a hang,
// a sanitizer report, or a patch with a non-finite or zero area.
// The input is split at the first "\n@@MTL@@\n": before it the OBJ, after it the MTL "m.mtl".
#include <unistd.h>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "hrad/core/error.h"
#include "hrad/io/obj_reader.h"

namespace {

std::string scratch_dir() {
  static const std::string dir = [] {
    std::string d = (std::filesystem::temp_directory_path() / ("hrad-fuzz-" + std::to_string(getpid()))).string();
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string marker = "\n@@MTL@@\n";
  const std::size_t split = input.find(marker);
  const std::string obj = input.substr(0, split);
  const std::string mtl =
      split == std::string::npos ? "newmtl w\nKd 0.5 0.5 0.5\n" : input.substr(split + marker.size());
  const std::string dir = scratch_dir();
  std::ofstream(dir + "/s.obj", std::ios::binary) << obj;
  std::ofstream(dir + "/m.mtl", std::ios::binary) << mtl;
  try {
    const hrad::Scene scene = hrad::read_obj_scene(dir + "/s.obj");
    for (const hrad::Patch& p : scene.patches) {
      if (!(p.area > 0.0) || !std::isfinite(p.area) || !p.normal.allFinite()) std::abort();
      if (p.vertices.size() < 3) std::abort();
    }
  } catch (const hrad::Error&) {
  }
  return 0;
}
