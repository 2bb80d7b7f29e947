#include "render/firefly_clamp.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace tuneray {

ClampThresholds ClampThresholds::uniform(float m) {
  ClampThresholds t;
  t.uniform_ = m;
  return t;
}

ClampThresholds ClampThresholds::relative(const Film& film, float k) {
  const int w = film.width(), h = film.height();
  const double image_mean = film.mean_value_length();
  if (!(image_mean > 0) || !(k > 0)) return {};
  std::vector<float> lengths(static_cast<size_t>(w) * h, -1.0f);  // -1: no samples
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x)
      if (uint32_t n = film.samples(x, y))
        lengths[static_cast<size_t>(y) * w + x] = length(film.sum(x, y)) / static_cast<float>(n);
  });
  ClampThresholds t;
  t.per_pixel_.resize(lengths.size());
  const float floor = static_cast<float>(image_mean);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      float sum = 0;
      int count = 0;
      for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1); ++yy)
        for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1); ++xx) {
          float v = lengths[static_cast<size_t>(yy) * w + xx];
          if (v < 0) continue;
          sum += v;
          ++count;
        }
      float local = count > 0 ? sum / static_cast<float>(count) : 0.0f;
      t.per_pixel_[static_cast<size_t>(y) * w + x] = k * std::max(local, floor);
    }
  });
  return t;
}

}  // namespace tuneray
