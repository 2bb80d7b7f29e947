#include "render/wave_pixel_order.h"

#include <cstddef>

namespace tuneray {

namespace {

constexpr int kBlock = 8;

// Bits of a 3-bit coordinate spread to the even bits (x) of a 6-bit Morton index.
constexpr int spread3(int v) {
  return (v & 1) | ((v & 2) << 1) | ((v & 4) << 2);
}

}  // namespace

std::vector<uint32_t> wave_pixel_order(int width, int height) {
  if (width <= 0 || height <= 0) return {};
  // The block's (x, y) in Morton order, once.
  int morton_x[kBlock * kBlock], morton_y[kBlock * kBlock];
  for (int y = 0; y < kBlock; ++y)
    for (int x = 0; x < kBlock; ++x) {
      const int m = spread3(x) | (spread3(y) << 1);
      morton_x[m] = x;
      morton_y[m] = y;
    }
  std::vector<uint32_t> order;
  order.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int y0 = 0; y0 < height; y0 += kBlock)
    for (int x0 = 0; x0 < width; x0 += kBlock)
      for (int m = 0; m < kBlock * kBlock; ++m) {
        const int x = x0 + morton_x[m], y = y0 + morton_y[m];
        if (x < width && y < height)
          order.push_back(static_cast<uint32_t>(static_cast<std::size_t>(y) * width + x));
      }
  return order;
}

}  // namespace tuneray
