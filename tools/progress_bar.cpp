#include "progress_bar.h"

#include <unistd.h>
#include <cstdio>
#include <string>

namespace hrad::cli {

void show_progress(int done, int total, std::string_view what) {
  constexpr int kWidth = 30;
  const int filled = total > 0 ? kWidth * done / total : kWidth;
  const std::string bar = std::string(filled, '#') + std::string(kWidth - filled, '.');
  const bool tty = isatty(fileno(stderr));
  std::fprintf(stderr, "%s[%s] %3d/%-3d %.*s%s", tty ? "\r\033[K" : "", bar.c_str(), done, total,
               static_cast<int>(what.size()), what.data(), tty && done < total ? "" : "\n");
  std::fflush(stderr);
}

void show_line(std::string_view line) {
  std::fprintf(stderr, "%s%.*s\n", isatty(fileno(stderr)) ? "\r\033[K" : "", static_cast<int>(line.size()),
               line.data());
  std::fflush(stderr);
}

}  // namespace hrad::cli
