// Lane-wise table lookups (render/simd8_lookup.h): every table size reads what indexing the
// table one lane at a time reads, across the permute (up to 8 and 16 entries) and gather paths.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "render/simd8_lookup.h"

namespace tuneray {
namespace {

TEST(Simd8Lookup, EveryTableSizeReadsTheIndexedEntries) {
  for (size_t entries = 1; entries <= 40; ++entries) {
    std::vector<float> floats(entries);
    std::vector<int32_t> ints(entries);
    for (size_t j = 0; j < entries; ++j) {
      floats[j] = 0.5f + static_cast<float>(j) * 1.25f;
      ints[j] = static_cast<int32_t>(1000 + 7 * j);
    }
    simd::pad_for_lookup(floats);
    simd::pad_for_lookup(ints);
    ASSERT_EQ(floats.size() % simd::kLanes, 0u);
    ASSERT_GE(floats.size(), entries);
    // Several index sets per size: each lane walks the table at its own stride, so every
    // entry, the first and the last included, appears in every lane.
    for (size_t start = 0; start < entries; ++start) {
      alignas(32) int32_t index[simd::kLanes];
      for (int lane = 0; lane < simd::kLanes; ++lane)
        index[lane] =
            static_cast<int32_t>((start + static_cast<size_t>(lane) * (lane + 3)) % entries);
      const simd::I8 at = simd::I8::load(index);
      alignas(32) float got_float[simd::kLanes];
      alignas(32) int32_t got_int[simd::kLanes];
      simd::lookup(floats, entries, at).store(got_float);
      simd::lookup(ints, entries, at).store(got_int);
      for (int lane = 0; lane < simd::kLanes; ++lane) {
        EXPECT_EQ(got_float[lane], floats[static_cast<size_t>(index[lane])])
            << entries << " entries, lane " << lane;
        EXPECT_EQ(got_int[lane], ints[static_cast<size_t>(index[lane])])
            << entries << " entries, lane " << lane;
      }
    }
  }
}

TEST(Simd8Lookup, PaddingIsWholeRegistersOfZeros) {
  EXPECT_EQ(simd::lookup_table_size(0), 8u);
  EXPECT_EQ(simd::lookup_table_size(8), 8u);
  EXPECT_EQ(simd::lookup_table_size(9), 16u);
  EXPECT_EQ(simd::lookup_table_size(17), 24u);
  std::vector<float> t{1.0f, 2.0f, 3.0f};
  simd::pad_for_lookup(t);
  ASSERT_EQ(t.size(), 8u);
  for (size_t j = 3; j < 8; ++j) EXPECT_EQ(t[j], 0.0f);
}

}  // namespace
}  // namespace tuneray
