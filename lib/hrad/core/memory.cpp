#include "hrad/core/memory.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <exception>

#include <sys/resource.h>
#include <unistd.h>

#include <fmt/format.h>

namespace hrad {

double available_memory_bytes() {
  double bytes = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  if (!(bytes > 0.0)) bytes = INFINITY;
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    struct rlimit limit {};
    if (getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      bytes = std::min(bytes, static_cast<double>(limit.rlim_cur));
  }
  return std::isfinite(bytes) ? bytes : 0.0;
}

std::string format_bytes(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.1f} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.0f} MB", bytes / 1e6);
  return fmt::format("{:.0f} kB", bytes / 1e3);
}

namespace {
// The record of the innermost scope an exception left: written once per exception (the first,
// innermost destructor), cleared when a scope is entered.
char g_failed[320];
std::atomic<bool> g_failed_set{false};
}  // namespace

AllocationScope::AllocationScope(std::string_view what, std::string_view remedy)
    : uncaught_(std::uncaught_exceptions()) {
  const auto end = fmt::format_to_n(text_, kTextSize - 1, "{}: {}", what, remedy);
  *end.out = '\0';
  g_failed_set.store(false);
}

AllocationScope::~AllocationScope() {
  if (std::uncaught_exceptions() > uncaught_ && !g_failed_set.exchange(true)) {
    static_assert(sizeof(g_failed) == kTextSize);
    std::memcpy(g_failed, text_, kTextSize);
  }
}

std::string failed_allocation() { return g_failed_set.load() ? std::string(g_failed) : std::string(); }

}  // namespace hrad
