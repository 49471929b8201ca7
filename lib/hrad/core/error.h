// User errors: bad files, bad options, bad JSON. Programmer errors are assertions instead.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace hrad {

/// A user-facing error whose message is one line that names where the problem is
/// ("scene.obj:12: face index 9 out of range (8 vertices)").
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// Error at `file:line`; line 0 means the file as a whole.
[[noreturn]] void throw_at(const std::string& file, std::size_t line, const std::string& message);

}  // namespace hrad
