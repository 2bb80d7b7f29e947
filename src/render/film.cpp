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

void Film::clear() {
  std::fill(sum_.data(), sum_.data() + sum_.pixel_count(), Color(0.0f));
  std::fill(samples_.begin(), samples_.end(), 0u);
}

}  // namespace tuneray
