// An allocator for the solvers' largest arrays (hundreds of MB to GB): on Linux it asks for
// transparent huge pages (2 MB) for blocks of 32 MB or more, so that first touching them faults
// 512x fewer pages (tests/bench/memory_benchmark.cpp measures first touch both ways). Elsewhere,
// or where the kernel refuses, it is plain operator new.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace hrad {

template <class T>
struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t kHugePage = std::size_t{2} << 20;
  static constexpr std::size_t kThreshold = std::size_t{32} << 20;

  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
#if defined(__linux__)
    if (bytes >= kThreshold) {
      const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
      void* p = std::aligned_alloc(kHugePage, rounded);
      if (!p) throw std::bad_alloc();
      madvise(p, rounded, MADV_HUGEPAGE);  // advice only: failure leaves ordinary pages
      return static_cast<T*>(p);
    }
#endif
    return static_cast<T*>(::operator new(bytes));
  }

  void deallocate(T* p, std::size_t n) noexcept {
#if defined(__linux__)
    if (n * sizeof(T) >= kThreshold) {
      std::free(p);
      return;
    }
#endif
    ::operator delete(p);
  }

  /// Default-initialises: a BigVector's resize(n) leaves trivial elements unwritten (the caller
  /// writes each once), so its pages are touched once, not zeroed and then written.
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }

  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

/// A vector for arrays that may reach GB. resize() and the size constructor leave trivial elements
/// uninitialised; pass a value to fill.
template <class T>
using BigVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace hrad
