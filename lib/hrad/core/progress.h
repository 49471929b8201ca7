// Progress of long work: counts done of a total, elapsed time and an estimate of the time left,
// one line at a time and at most one line every `interval_seconds`, so a log gets a line every
// second or two and short work prints nothing.
//
// Usage (any thread may call advance(); the line is sent by whichever call crosses the interval):
//
//   ProgressReporter progress("form factors", total_pairs, "pairs", options.progress);
//   ... progress.advance(pairs_done_in_this_block); ...
//   progress.finish();   // one closing line, only when a line was already printed
//
// The estimate is linear: the time per unit so far times the units left (eta_seconds()). For an
// iteration converging geometrically, iterations_left() extrapolates the change instead.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

namespace hrad {

using ProgressSink = std::function<void(std::string_view)>;

/// Seconds left when `done` of `total` units took `elapsed_seconds`, at the rate so far; nothing
/// when no unit is done yet (no rate) or the numbers are not usable. 0 when done >= total.
std::optional<double> eta_seconds(std::uint64_t done, std::uint64_t total, double elapsed_seconds);

/// Iterations still needed for a change that fell from `earlier_change` to `change` over `iterations`
/// iterations to reach `tolerance`, assuming the same geometric rate; nothing when the change did
/// not fall (no rate to extrapolate) or a number is not finite and positive. 0 when change <= tolerance.
std::optional<double> iterations_left(double earlier_change, double change, int iterations, double tolerance);

/// "4.2 s", "3 min 05 s", "2 h 07 min": durations as people read them.
std::string format_duration(double seconds);

/// "12,345": thousands separated by commas.
std::string format_count(std::uint64_t n);

/// "what: 1,200 / 5,000 unit (24%), 12.0 s, about 38.0 s left": the line ProgressReporter prints.
std::string progress_line(std::string_view what, std::uint64_t done, std::uint64_t total, std::string_view unit,
                          double elapsed_seconds);

class ProgressReporter {
 public:
  /// Seconds since some fixed start; steady_clock by default (tests pass their own).
  using Clock = std::function<double()>;

  /// `sink` may be empty: then nothing is printed (the counting still works).
  ProgressReporter(std::string what, std::uint64_t total, std::string unit, ProgressSink sink,
                   double interval_seconds = 2.0, Clock clock = {});
  ~ProgressReporter() = default;
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  /// Counts `n` more units done; prints a line when `interval_seconds` passed since the last one
  /// (or since the start). Thread-safe; cheap when no line is due (one atomic add and a clock read).
  void advance(std::uint64_t n = 1);
  /// Sets the count done (for loops that know it).
  void set_done(std::uint64_t done);
  /// Prints "what: done N unit in T" when at least one line was printed before (work long enough to
  /// show progress is long enough to say it ended). Idempotent.
  void finish();

  std::uint64_t done() const { return done_.load(std::memory_order_relaxed); }
  std::uint64_t total() const { return total_; }
  /// Lines sent to the sink so far.
  int lines() const { return lines_.load(std::memory_order_relaxed); }

 private:
  void maybe_print();
  double now() const;

  std::string what_, unit_;
  std::uint64_t total_;
  ProgressSink sink_;
  double interval_;
  Clock clock_;
  double start_;
  std::atomic<std::uint64_t> done_{0};
  std::atomic<double> next_line_at_;
  std::atomic<int> lines_{0};
  std::atomic<bool> finished_{false};
  std::mutex print_;
};

}  // namespace hrad
