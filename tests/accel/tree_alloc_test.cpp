// tree_alloc: the memory every tree of ours adopts (collapsed nodes, merged leaves, the static
// relayout). Buffers of 2 MiB or more are huge-page aligned and rounded to whole huge pages,
// smaller ones cache-line aligned; either way the whole size asked for is usable and freeing it
// returns it.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "accel/bvh_tree.h"
#include "resident_memory.h"

namespace tuneray::test {
namespace {

bool aligned_to(const void* p, size_t alignment) {
  return reinterpret_cast<uintptr_t>(p) % alignment == 0;
}

TEST(TreeAlloc, LargeBuffersAreHugePageAlignedSmallOnesLineAligned) {
  constexpr size_t kHugePage = size_t{2} << 20;
  for (size_t bytes : {kHugePage, 3 * kHugePage + 1, size_t{5} << 20}) {
    void* p = bvh::tree_alloc(bytes);
    EXPECT_TRUE(aligned_to(p, kHugePage)) << bytes;
    std::memset(p, 0xab, bytes);  // every byte asked for is writable (AddressSanitizer checks)
    std::free(p);
  }
  for (size_t bytes : {size_t{0}, size_t{1}, size_t{100}, kHugePage - 1}) {
    void* p = bvh::tree_alloc(bytes);
    ASSERT_NE(p, nullptr);
    EXPECT_TRUE(aligned_to(p, 64)) << bytes;
    std::memset(p, 0xcd, bytes);
    std::free(p);
  }
}

TEST(TreeAlloc, FreedHugeBuffersAreReturned) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "RSS is not meaningful under AddressSanitizer (quarantine)";
#endif
  constexpr size_t kBytes = size_t{9} << 20;
  auto touch_and_free = [] {
    void* p = bvh::tree_alloc(kBytes);
    std::memset(p, 1, kBytes);
    std::free(p);
  };
  touch_and_free();
  const size_t before = resident_bytes();
  for (int i = 0; i < 100; ++i) touch_and_free();
  // 100 leaked buffers would be 900 MiB; allow one buffer and its rounding.
  EXPECT_LT(resident_bytes(), before + 2 * kBytes);
}

}  // namespace
}  // namespace tuneray::test
