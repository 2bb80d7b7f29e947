#include "render/firefly_clamp.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "render/neighbourhood_mean.h"

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
  std::vector<float> local = neighbourhood_mean(lengths, w, h);
  ClampThresholds t;
  t.per_pixel_.resize(lengths.size());
  const float floor = static_cast<float>(image_mean);
  for (size_t i = 0; i < local.size(); ++i) t.per_pixel_[i] = k * std::max(local[i], floor);
  return t;
}

}  // namespace tuneray
