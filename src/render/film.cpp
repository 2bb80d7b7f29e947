#include "render/film.h"

#include <algorithm>

namespace tuneray {

Image Film::resolve() const {
  Image out(width(), height());
  for (int y = 0; y < height(); ++y)
    for (int x = 0; x < width(); ++x) {
      uint32_t n = samples(x, y);
      out.at(x, y) = n > 0 ? sum_.at(x, y) / static_cast<float>(n) : Color(0.0f);
    }
  return out;
}

double Film::variance_of_mean(int x, int y) const {
  size_t i = static_cast<size_t>(y) * width() + x;
  double n = samples_[i];
  if (n < 2) return 0.0;
  double mean = luminance(sum_.at(x, y)) / n;
  double variance = (luminance_sq_[i] - n * mean * mean) / (n - 1);
  return std::max(0.0, variance) / n;
}

void Film::clear() {
  std::fill(luminance_sq_.begin(), luminance_sq_.end(), 0.0);
  std::fill(sum_.data(), sum_.data() + sum_.pixel_count(), Color(0.0f));
  std::fill(samples_.begin(), samples_.end(), 0u);
}

}  // namespace tuneray
