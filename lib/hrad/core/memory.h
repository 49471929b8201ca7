// How much memory this process may use, for refusing oversized work up front (a clear message with
// the option to change, instead of std::bad_alloc halfway through).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace hrad {

/// The smaller of the machine's physical memory and the process's address-space and data limits
/// (ulimit -v, ulimit -d), in bytes; 0 when none is known.
double available_memory_bytes();

/// "1.2 GB", "340 MB": a byte count for messages.
std::string format_bytes(double bytes);

/// Names what the work inside it allocates and how to make that smaller, so that running out of
/// memory ends in "out of memory while allocating the links of the refinement: raise --aeps" rather
/// than std::bad_alloc. Scopes nest (a solve, its phases). When an exception leaves a scope, the
/// innermost scope it leaves is remembered for the handler that catches it (failed_allocation());
/// that path allocates nothing (fixed buffers), since memory may have run out. Entering a scope
/// forgets an earlier record, so one from an exception handled inside the work does not linger.
/// One process-wide record: scopes belong to the thread that runs the work (worker threads'
/// exceptions reach it through their parallel loops).
class AllocationScope {
 public:
  /// what: "the links of the refinement"; remedy: "raise --aeps or --feps".
  AllocationScope(std::string_view what, std::string_view remedy);
  ~AllocationScope();
  AllocationScope(const AllocationScope&) = delete;
  AllocationScope& operator=(const AllocationScope&) = delete;

 private:
  static constexpr std::size_t kTextSize = 320;
  char text_[kTextSize];
  int uncaught_;
};

/// "the links of the refinement: raise --aeps or --feps" of the innermost scope the last exception
/// left, or "" when no exception left a scope since one was last entered.
std::string failed_allocation();

}  // namespace hrad
