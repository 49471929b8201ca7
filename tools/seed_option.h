// The `--seed` of every subcommand: a whole number that fits 64 bits. CLI11 converts "-1" and
// "99999999999999999999" into a std::uint64_t without complaint (wrapping them), so the text is
// checked before it is converted.
#pragma once

#include <charconv>
#include <cstdint>
#include <limits>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

namespace hrad::cli {

inline CLI::Validator seed_validator() {
  return CLI::Validator(
      [](std::string& text) {
        std::uint64_t value = 0;
        const char* last = text.data() + text.size();
        const auto [end, ec] = std::from_chars(text.data(), last, value);
        if (!text.empty() && ec == std::errc() && end == last) return std::string();
        return fmt::format("must be a whole number in [0, {}], got '{}'", std::numeric_limits<std::uint64_t>::max(),
                           text);
      },
      "UINT");
}

}  // namespace hrad::cli
