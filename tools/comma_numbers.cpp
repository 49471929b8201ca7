#include "comma_numbers.h"

#include <algorithm>
#include <cmath>
#include <exception>

namespace hrad::cli {

std::optional<std::vector<double>> comma_numbers(const std::string& text) {
  std::vector<double> values;
  std::size_t begin = 0;
  while (true) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      return std::nullopt;
    }
    if (used != item.size() || !std::isfinite(x)) return std::nullopt;
    values.push_back(x);
    if (end == text.size()) return values;
    begin = end + 1;
  }
}

}  // namespace hrad::cli
