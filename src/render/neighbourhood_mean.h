// Mean of a per-pixel quantity over each pixel's 3x3 neighbourhood: per-pixel estimates from a
// few samples are noisy, and the quantities they estimate (variance, brightness) are spatially
// coherent. Used by adaptive sampling and the relative firefly clamp.
#pragma once

#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

namespace tuneray {

namespace detail {

// Any values, negative ones skipped: nine reads and tests per pixel.
template <class T>
std::vector<T> neighbourhood_mean_masked(const std::vector<T>& values, int width, int height) {
  std::vector<T> out(values.size());
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      T sum = 0;
      int count = 0;
      for (int yy = std::max(0, y - 1); yy <= std::min(height - 1, y + 1); ++yy)
        for (int xx = std::max(0, x - 1); xx <= std::min(width - 1, x + 1); ++xx) {
          T v = values[static_cast<size_t>(yy) * width + xx];
          if (v < 0) continue;
          sum += v;
          ++count;
        }
      out[static_cast<size_t>(y) * width + x] = count > 0 ? sum / static_cast<T>(count) : T(0);
    }
  });
  return out;
}

// No value negative: sums of three along each row, then of three such sums down each column,
// divided by the window's size (9 inside, 6 or 4 at the border).
template <class T>
std::vector<T> neighbourhood_mean_separable(const std::vector<T>& values, int width, int height) {
  std::vector<T> rows(values.size()), out(values.size());
  tbb::parallel_for(0, height, [&](int y) {
    const T* in = &values[static_cast<size_t>(y) * width];
    T* r = &rows[static_cast<size_t>(y) * width];
    for (int x = 0; x < width; ++x) {
      T sum = in[x];
      if (x > 0) sum += in[x - 1];
      if (x + 1 < width) sum += in[x + 1];
      r[x] = sum;
    }
  });
  tbb::parallel_for(0, height, [&](int y) {
    const T* mid = &rows[static_cast<size_t>(y) * width];
    const T* up = y > 0 ? mid - width : nullptr;
    const T* down = y + 1 < height ? mid + width : nullptr;
    const int rows_in = 1 + (up ? 1 : 0) + (down ? 1 : 0);
    T* o = &out[static_cast<size_t>(y) * width];
    for (int x = 0; x < width; ++x) {
      T sum = mid[x];
      if (up) sum += up[x];
      if (down) sum += down[x];
      const int cols_in = 1 + (x > 0 ? 1 : 0) + (x + 1 < width ? 1 : 0);
      o[x] = sum / static_cast<T>(rows_in * cols_in);
    }
  });
  return out;
}

}  // namespace detail

// `values` is row-major, width x height. Negative values mark pixels without data: they are left
// out of their neighbours' means, and a pixel with no data around it gets 0. The border clips.
// Without negative values (adaptive sampling's variances) the mean is taken separably, a third
// of the reads.
template <class T>
std::vector<T> neighbourhood_mean(const std::vector<T>& values, int width, int height) {
  bool any_negative = false;
  for (T v : values) any_negative |= v < 0;
  return any_negative ? detail::neighbourhood_mean_masked(values, width, height)
                      : detail::neighbourhood_mean_separable(values, width, height);
}

}  // namespace tuneray
