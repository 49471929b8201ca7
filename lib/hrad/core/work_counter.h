// A count of work that many threads add to: one cache line per thread, summed when read.
//
// A single std::atomic counter that every thread increments moves its cache line between the cores
// on every increment: a solve that counts each of its ~3e8 segment queries so spent ~12% more CPU
// on two threads than on one (the generated 4,400-polygon pillar hall, 37.4 -> 42.3 s), where two
// separate one-thread solves run side by side lost nothing. Each thread here adds to a slot of its
// own (relaxed load and store, no locked instruction); threads beyond the slots share the last one
// by fetch_add. Reads are exact once the adding threads have finished (the join of a
// parallel_for orders their stores before the read).
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace hrad {

namespace detail {
/// This thread's slot in every WorkCounter: 0, 1, 2, ... in the order threads first count.
std::size_t work_counter_slot();
}  // namespace detail

class WorkCounter {
 public:
  static constexpr std::size_t kSlots = 32;

  WorkCounter() = default;
  WorkCounter(const WorkCounter&) = delete;
  WorkCounter& operator=(const WorkCounter&) = delete;

  void add(std::uint64_t n = 1) noexcept {
    thread_local const std::size_t slot = detail::work_counter_slot();
    if (slot + 1 < kSlots) {
      std::atomic<std::uint64_t>& c = slots_[slot].count;
      c.store(c.load(std::memory_order_relaxed) + n, std::memory_order_relaxed);
    } else {
      slots_[kSlots - 1].count.fetch_add(n, std::memory_order_relaxed);
    }
  }
  std::uint64_t load() const noexcept {
    std::uint64_t sum = 0;
    for (const Slot& s : slots_) sum += s.count.load(std::memory_order_relaxed);
    return sum;
  }
  void reset() noexcept {
    for (Slot& s : slots_) s.count.store(0, std::memory_order_relaxed);
  }

 private:
  struct alignas(64) Slot {
    std::atomic<std::uint64_t> count{0};
  };
  std::array<Slot, kSlots> slots_{};
};

}  // namespace hrad
