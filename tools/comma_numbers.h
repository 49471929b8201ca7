// Option values that are lists of numbers ("--camera 1,2,3,...", "--feps 0.1,0.01").
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace hrad::cli {

/// The comma-separated numbers in `text`, or nothing when an item is empty, is not a whole number,
/// or is not finite. Callers word their own error, naming their option.
std::optional<std::vector<double>> comma_numbers(const std::string& text);

}  // namespace hrad::cli
