// An allocator for large float planes that the same loop streams side by side. Equal-sized
// large allocations start at the same offset within a 4 KiB page, so the same pixel of every
// plane falls in the same L1 cache set; a loop reading ~20 planes at once then evicts its own
// lines (L1 holds 8 ways per set). Each allocation here is shifted by a different number of
// cache lines, which spreads the planes over the sets. The contents are unaffected.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstring>
#include <new>
#include <vector>

namespace tuneray {

template <class T>
struct StaggeredAllocator {
  using value_type = T;
  static constexpr size_t kLine = 64;
  static constexpr size_t kShifts = 61;  // distinct shifts, 1 to 61 lines: all within a page

  StaggeredAllocator() = default;
  template <class U>
  StaggeredAllocator(const StaggeredAllocator<U>&) {}

  T* allocate(size_t n) {
    static std::atomic<size_t> next{0};
    const size_t shift = kLine * (1 + next.fetch_add(1, std::memory_order_relaxed) % kShifts);
    char* raw = static_cast<char*>(::operator new(n * sizeof(T) + shift, std::align_val_t(kLine)));
    char* p = raw + shift;
    std::memcpy(p - sizeof(size_t), &shift, sizeof(size_t));  // for deallocate
    return reinterpret_cast<T*>(p);
  }
  void deallocate(T* p, size_t) {
    char* c = reinterpret_cast<char*>(p);
    size_t shift;
    std::memcpy(&shift, c - sizeof(size_t), sizeof(size_t));
    ::operator delete(c - shift, std::align_val_t(kLine));
  }
  template <class U>
  bool operator==(const StaggeredAllocator<U>&) const {
    return true;
  }
};

// A plane of floats for the denoiser's tap loops.
using FloatPlane = std::vector<float, StaggeredAllocator<float>>;

}  // namespace tuneray
