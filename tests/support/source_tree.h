// Where the tests find the source tree's files and the `hrad` executable. Only
// source_tree.cpp is compiled with these paths, so every other test translation unit is the same in
// any clone and ccache serves it from a build of another clone (CMakeLists.txt, HRAD_CCACHE).
#pragma once

#include <string>

namespace hrad::test {

const std::string& source_dir();       ///< the source tree's root, without a trailing '/'
const std::string& hrad_executable();  ///< build/bin/hrad

}  // namespace hrad::test
