#include "hrad/core/error.h"

namespace hrad {

void throw_at(const std::string& file, std::size_t line, const std::string& message) {
  if (line == 0) throw Error(file + ": " + message);
  throw Error(file + ":" + std::to_string(line) + ": " + message);
}

}  // namespace hrad
