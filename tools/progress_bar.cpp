#include "progress_bar.h"

#include <cstdio>
#include <string>
#include <unistd.h>

#include <fmt/format.h>

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

EtaProgress::EtaProgress(std::string unit, double delay_seconds)
    : unit_(std::move(unit)), delay_seconds_(delay_seconds) {}

void EtaProgress::operator()(std::size_t done, std::size_t total) {
  const double elapsed = clock_.seconds();
  const bool last = done >= total;
  if (elapsed < delay_seconds_ && last_drawn_ < 0.0) return;
  const double interval = isatty(fileno(stderr)) ? 0.25 : 10.0;
  if (!last && last_drawn_ >= 0.0 && elapsed - last_drawn_ < interval) return;
  last_drawn_ = elapsed;
  const std::string left =
      last ? "done" : done == 0 ? "time left unknown"
                                : fmt::format("~{:.1f} s left", elapsed * static_cast<double>(total - done) / static_cast<double>(done));
  show_progress(static_cast<int>(done), static_cast<int>(total),
                fmt::format("{}, {:.1f} s elapsed, {}", unit_, elapsed, left));
}

}  // namespace hrad::cli
