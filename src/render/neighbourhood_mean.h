// Mean of a per-pixel quantity over each pixel's 3x3 neighbourhood: per-pixel estimates from a
// few samples are noisy, and the quantities they estimate (variance, brightness) are spatially
// coherent. Used by adaptive sampling and the relative firefly clamp.
#pragma once

#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

namespace tuneray {

// `values` is row-major, width x height. Negative values mark pixels without data: they are left
// out of their neighbours' means, and a pixel with no data around it gets 0. The border clips.
template <class T>
std::vector<T> neighbourhood_mean(const std::vector<T>& values, int width, int height) {
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

}  // namespace tuneray
