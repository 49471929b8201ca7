#include "support/source_tree.h"

namespace hrad::test {

const std::string& source_dir() {
  static const std::string dir = HRAD_SOURCE_DIR;
  return dir;
}

const std::string& hrad_executable() {
  static const std::string path = HRAD_EXECUTABLE;
  return path;
}

}  // namespace hrad::test
