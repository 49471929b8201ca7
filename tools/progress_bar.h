// A progress bar on stderr for long subcommands: redrawn in place on a terminal, one line per
// step otherwise (logs, CI).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "hrad/core/stopwatch.h"

namespace hrad::cli {

/// Draws "[#####.....]  5/10  what" on stderr.
void show_progress(int done, int total, std::string_view what);

/// Progress with the time elapsed and an estimate of the time left ("120/500 points, 3.1 s
/// elapsed, ~9.8 s left"), for runs long enough to need it: silent for the first `delay_seconds`,
/// then redrawn at most 4 times a second on a terminal and every 10 s otherwise; the last line is
/// drawn whenever the run took longer than the delay. The estimate assumes the remaining items cost what the done ones did.
class EtaProgress {
 public:
  explicit EtaProgress(std::string unit, double delay_seconds = 2.0);
  void operator()(std::size_t done, std::size_t total);

 private:
  std::string unit_;
  double delay_seconds_;
  Stopwatch clock_;
  double last_drawn_ = -1.0;
};

}  // namespace hrad::cli
