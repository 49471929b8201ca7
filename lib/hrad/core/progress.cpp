#include "hrad/core/progress.h"

#include <cmath>

#include <fmt/format.h>

namespace hrad {

std::optional<double> eta_seconds(std::uint64_t done, std::uint64_t total, double elapsed_seconds) {
  if (done >= total) return 0.0;
  if (done == 0 || !std::isfinite(elapsed_seconds) || elapsed_seconds < 0.0) return std::nullopt;
  return elapsed_seconds / static_cast<double>(done) * static_cast<double>(total - done);
}

std::optional<double> iterations_left(double earlier_change, double change, int iterations, double tolerance) {
  if (!(std::isfinite(change) && std::isfinite(earlier_change) && std::isfinite(tolerance)) || !(tolerance > 0.0) ||
      iterations < 1)
    return std::nullopt;
  if (change <= tolerance) return 0.0;
  if (!(earlier_change > change) || !(change > 0.0)) return std::nullopt;
  // change_k = change * r^k with r = (change / earlier)^(1 / iterations); solve change * r^k = tolerance.
  const double log_rate = std::log(change / earlier_change) / iterations;
  return std::ceil(std::log(tolerance / change) / log_rate);
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  if (seconds < 60.0) return fmt::format("{:.1f} s", seconds);
  const auto whole = static_cast<long long>(std::llround(seconds));
  if (whole < 3600) return fmt::format("{} min {:02} s", whole / 60, whole % 60);
  return fmt::format("{} h {:02} min", whole / 3600, (whole % 3600) / 60);
}

std::string format_count(std::uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string progress_line(std::string_view what, std::uint64_t done, std::uint64_t total, std::string_view unit,
                          double elapsed_seconds) {
  const double percent = total > 0 ? 100.0 * static_cast<double>(done) / static_cast<double>(total) : 100.0;
  std::string line = fmt::format("{}: {} / {} {} ({:.0f}%), {}", what, format_count(done), format_count(total), unit,
                                 percent, format_duration(elapsed_seconds));
  if (const std::optional<double> eta = eta_seconds(done, total, elapsed_seconds); eta && done < total)
    line += fmt::format(", about {} left", format_duration(*eta));
  return line;
}

ProgressReporter::ProgressReporter(std::string what, std::uint64_t total, std::string unit, ProgressSink sink,
                                   double interval_seconds, Clock clock)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(total),
      sink_(std::move(sink)),
      interval_(interval_seconds),
      clock_(std::move(clock)),
      start_(now()),
      next_line_at_(start_ + interval_seconds) {}

double ProgressReporter::now() const {
  if (clock_) return clock_();
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void ProgressReporter::advance(std::uint64_t n) {
  done_.fetch_add(n, std::memory_order_relaxed);
  maybe_print();
}

void ProgressReporter::set_done(std::uint64_t done) {
  done_.store(done, std::memory_order_relaxed);
  maybe_print();
}

void ProgressReporter::maybe_print() {
  if (!sink_) return;
  const double t = now();
  double due = next_line_at_.load(std::memory_order_relaxed);
  if (t < due) return;
  // One thread wins the right to print this line; the others go back to work.
  if (!next_line_at_.compare_exchange_strong(due, t + interval_, std::memory_order_relaxed)) return;
  const std::lock_guard<std::mutex> lock(print_);
  if (finished_.load()) return;
  sink_(progress_line(what_, std::min(done(), total_), total_, unit_, t - start_));
  lines_.fetch_add(1, std::memory_order_relaxed);
}

void ProgressReporter::finish() {
  const std::lock_guard<std::mutex> lock(print_);
  if (finished_.exchange(true)) return;
  if (sink_ && lines_.load() > 0) {
    sink_(fmt::format("{}: done, {} {} in {}", what_, format_count(done()), unit_, format_duration(now() - start_)));
    lines_.fetch_add(1, std::memory_order_relaxed);
  }
}

}  // namespace hrad
