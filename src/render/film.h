// Progressive accumulation: a running sum of radiance and a sample count per pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.h"

namespace tuneray {

class Film {
 public:
  Film(int width, int height)
      : sum_(width, height), samples_(static_cast<size_t>(width) * height, 0) {}

  int width() const { return sum_.width(); }
  int height() const { return sum_.height(); }

  // Single writer per pixel (tiles do not overlap), so no synchronisation.
  void add(int x, int y, Color radiance_sum, uint32_t count) {
    sum_.at(x, y) += radiance_sum;
    samples_[static_cast<size_t>(y) * width() + x] += count;
  }
  uint32_t samples(int x, int y) const { return samples_[static_cast<size_t>(y) * width() + x]; }

  // The current estimate (sum / count per pixel).
  Image resolve() const;
  void clear();

 private:
  Image sum_;
  std::vector<uint32_t> samples_;
};

}  // namespace tuneray
