#include "hrad/io/csv_number.h"

#include <charconv>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "hrad/core/error.h"

namespace hrad {

double parse_csv_number(const std::string& path, std::size_t line, const std::string& column, const char* text) {
  std::string_view cell(text);
  if (cell.empty()) throw_at(path, line, fmt::format("column {}: empty cell", column));
  std::string_view digits = cell;
  if (digits.front() == '+') digits.remove_prefix(1);  // from_chars takes no '+'
  double value = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec == std::errc::result_out_of_range)
    throw_at(path, line, fmt::format("column {}: '{}' is out of the range of a double", column, cell));
  if (ec != std::errc() || end != digits.data() + digits.size())
    throw_at(path, line, fmt::format("column {}: '{}' is not a number", column, cell));
  if (!std::isfinite(value)) throw_at(path, line, fmt::format("column {}: '{}' is not finite", column, cell));
  return value;
}

}  // namespace hrad
