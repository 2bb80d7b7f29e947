// Progressive accumulation: a running sum of radiance and a sample count per pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.h"

namespace tuneray {

class Film {
 public:
  Film(int width, int height)
      : sum_(width, height),
        samples_(static_cast<size_t>(width) * height, 0),
        luminance_sq_(static_cast<size_t>(width) * height, 0.0) {}

  int width() const { return sum_.width(); }
  int height() const { return sum_.height(); }

  // Single writer per pixel (tiles do not overlap), so no synchronisation.
  // `luminance_sq_sum` is the sum of the squared luminances of the samples (for the variance
  // estimate of adaptive sampling).
  void add(int x, int y, Color radiance_sum, uint32_t count, double luminance_sq_sum = 0) {
    sum_.at(x, y) += radiance_sum;
    size_t i = static_cast<size_t>(y) * width() + x;
    samples_[i] += count;
    luminance_sq_[i] += luminance_sq_sum;
  }
  uint32_t samples(int x, int y) const { return samples_[static_cast<size_t>(y) * width() + x]; }

  // Estimated variance of the pixel's mean luminance (sample variance / n); 0 below 2 samples.
  double variance_of_mean(int x, int y) const;

  // The current estimate (sum / count per pixel).
  Image resolve() const;
  void clear();

 private:
  Image sum_;
  std::vector<uint32_t> samples_;
  std::vector<double> luminance_sq_;
};

}  // namespace tuneray
