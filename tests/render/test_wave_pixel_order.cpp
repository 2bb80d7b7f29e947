// The order in which the wavefront scheduler takes pixels (render/wave_pixel_order.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "render/wave_pixel_order.h"

namespace tuneray {
namespace {

TEST(WavePixelOrder, IsAPermutationOfThePixelsForEveryImageShape) {
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{
           {1, 1}, {8, 8}, {7, 3}, {9, 17}, {320, 180}, {33, 1}, {1, 33}}) {
    SCOPED_TRACE(::testing::Message() << w << "x" << h);
    std::vector<uint32_t> order = wave_pixel_order(w, h);
    ASSERT_EQ(order.size(), static_cast<size_t>(w) * h);
    std::sort(order.begin(), order.end());
    for (size_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i);
  }
  EXPECT_TRUE(wave_pixel_order(0, 5).empty());
  EXPECT_TRUE(wave_pixel_order(5, -1).empty());
}

// Every aligned run of 4^k pixels (k <= 3) inside a whole block is a 2^k × 2^k square: what a
// stream of 64 camera rays (or 16 pixels of 4 samples) covers.
TEST(WavePixelOrder, AlignedRunsOfWholeBlocksAreSquares) {
  const int w = 40, h = 24;  // whole 8×8 blocks only
  const std::vector<uint32_t> order = wave_pixel_order(w, h);
  for (int side : {2, 4, 8}) {
    const size_t run = static_cast<size_t>(side) * side;
    for (size_t first = 0; first < order.size(); first += run) {
      int x0 = w, y0 = h, x1 = -1, y1 = -1;
      for (size_t k = first; k < first + run; ++k) {
        const int x = static_cast<int>(order[k] % w), y = static_cast<int>(order[k] / w);
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
      ASSERT_EQ(x1 - x0 + 1, side) << "run at " << first;
      ASSERT_EQ(y1 - y0 + 1, side) << "run at " << first;
      ASSERT_EQ(x0 % side, 0);
      ASSERT_EQ(y0 % side, 0);
    }
  }
}

// Blocks go left to right along a band of 8 rows, then the next band; the first pixels are the
// Morton order's (0,0), (1,0), (0,1), (1,1), (2,0).
TEST(WavePixelOrder, BlocksFollowTheBandsAndStartInMortonOrder) {
  const int w = 20, h = 13;
  const std::vector<uint32_t> order = wave_pixel_order(w, h);
  const std::vector<uint32_t> first = {0, 1, static_cast<uint32_t>(w), static_cast<uint32_t>(w + 1),
                                       2};
  for (size_t k = 0; k < first.size(); ++k) EXPECT_EQ(order[k], first[k]);
  int last_band = 0, last_block_x = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    const int band = static_cast<int>(order[k] / w) / 8,
              block_x = static_cast<int>(order[k] % w) / 8;
    ASSERT_GE(band, last_band);
    if (band == last_band) {
      ASSERT_GE(block_x, last_block_x);
    }
    last_band = band;
    last_block_x = block_x;
  }
  // The cut block at the right edge (x 16..19) of the first band holds 4 × 8 pixels.
  const auto cut = std::count_if(order.begin(), order.begin() + 8 * w,
                                 [&](uint32_t p) { return static_cast<int>(p % w) >= 16; });
  EXPECT_EQ(cut, 32);
}

}  // namespace
}  // namespace tuneray
