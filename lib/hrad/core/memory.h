// How much memory this process may use, for refusing oversized work up front (a clear message with
// the option to change, instead of std::bad_alloc halfway through).
#pragma once

#include <cstddef>
#include <string>

namespace hrad {

/// The smaller of the machine's physical memory and the process's address-space and data limits
/// (ulimit -v, ulimit -d), in bytes; 0 when none is known.
double available_memory_bytes();

/// "1.2 GB", "340 MB": a byte count for messages.
std::string format_bytes(double bytes);

}  // namespace hrad
