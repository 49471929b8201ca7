// WorkCounter: what many threads add is all there when read, also with more threads than slots.
#include <gtest/gtest.h>

#include <cstdint>
#include <thread>
#include <vector>

#include "hrad/core/work_counter.h"

namespace hrad {
namespace {

// Guarantee: the sum of every thread's additions, exactly, whether each thread has a slot of its
// own or (beyond WorkCounter::kSlots threads) shares the last one.
TEST(WorkCounter, SumsWhatEveryThreadAdded) {
  WorkCounter c;
  const int threads = static_cast<int>(WorkCounter::kSlots) + 8;
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&c, t] {
      for (int i = 0; i < 10000; ++i) c.add(static_cast<std::uint64_t>(t % 3 + 1));
    });
  for (std::thread& t : pool) t.join();
  std::uint64_t expected = 0;
  for (int t = 0; t < threads; ++t) expected += 10000u * static_cast<std::uint64_t>(t % 3 + 1);
  EXPECT_EQ(c.load(), expected);
  c.reset();
  EXPECT_EQ(c.load(), 0u);
  c.add();
  EXPECT_EQ(c.load(), 1u);
}

}  // namespace
}  // namespace hrad
