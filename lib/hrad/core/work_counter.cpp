#include "hrad/core/work_counter.h"

namespace hrad::detail {

std::size_t work_counter_slot() {
  static std::atomic<std::size_t> next{0};
  return next.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace hrad::detail
