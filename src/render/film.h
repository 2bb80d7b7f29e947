// Progressive accumulation: a running sum of radiance and a sample count per pixel.
#pragma once

#include <cstdint>
#include <vector>

#include "image/image.h"

namespace tuneray {

// Per-channel sums of squared sample values: with the sum and count, a pixel's variance in the
// same terms as our RMSE (r, g and b counted as separate values).
struct SquareSum {
  double r = 0, g = 0, b = 0;
  void add(Color c) {
    r += static_cast<double>(c.x) * c.x;
    g += static_cast<double>(c.y) * c.y;
    b += static_cast<double>(c.z) * c.z;
  }
  static SquareSum of(Color c) {
    SquareSum s;
    s.add(c);
    return s;
  }
};

// One pixel's samples of a pass, with their indices' parity: the film also keeps two half
// films (even and odd sample indices), independent estimates of the same pixel that let the
// denoiser measure its own error (render/denoiser_selection.h).
struct PixelSamples {
  Color sum{0.0f};
  uint32_t count = 0;
  SquareSum squares;
  Color half_sum[2] = {Color(0.0f), Color(0.0f)};
  uint32_t half_count[2] = {0, 0};
  void add(Color radiance, uint32_t sample_index) {
    sum += radiance;
    ++count;
    squares.add(radiance);
    half_sum[sample_index & 1] += radiance;
    ++half_count[sample_index & 1];
  }
};

class Film {
 public:
  // Upper bound of a render's memory per pixel: the film (sum, count, squares, two halves),
  // the resolved image and its file encoding, the schedulers' and adaptive sampling's
  // per-pixel arrays.
  static constexpr uint64_t kBytesPerPixelBound = 160;

  Film(int width, int height)
      : sum_(width, height),
        samples_(static_cast<size_t>(width) * height, 0),
        square_sum_(static_cast<size_t>(width) * height),
        half_sum_{Image(width, height), Image(width, height)},
        half_samples_{std::vector<uint32_t>(static_cast<size_t>(width) * height, 0),
                      std::vector<uint32_t>(static_cast<size_t>(width) * height, 0)} {}

  int width() const { return sum_.width(); }
  int height() const { return sum_.height(); }

  // Single writer per pixel (tiles do not overlap), so no synchronisation. `squares` sums the
  // samples' squared channels (variance estimates for adaptive sampling and error estimates).
  // Samples given without their indices all go to the half of the pixel's sample count's
  // parity, so one-sample adds alternate between the halves as the schedulers' indices do.
  void add(int x, int y, Color radiance_sum, uint32_t count, const SquareSum& squares = {}) {
    const size_t i = static_cast<size_t>(y) * width() + x;
    const int half = samples_[i] & 1;
    add_full(i, x, y, radiance_sum, count, squares);
    half_sum_[half].at(x, y) += radiance_sum;
    half_samples_[half][i] += count;
  }
  void add(int x, int y, const PixelSamples& s) {
    const size_t i = static_cast<size_t>(y) * width() + x;
    add_full(i, x, y, s.sum, s.count, s.squares);
    for (int h = 0; h < 2; ++h) {
      half_sum_[h].at(x, y) += s.half_sum[h];
      half_samples_[h][i] += s.half_count[h];
    }
  }
  // Asks for pixel (x, y)'s lines in every array an add writes, ahead of the add: the
  // schedulers add pixels in blocks (wave_pixel_order.h), whose rows are too short for the
  // hardware's stream prefetchers, and a 640×360 film is larger than the caches. Always
  // inlined: GCC 12 finds an out-of-line copy free of side effects and deletes its calls.
  [[gnu::always_inline]] void prefetch(int x, int y) const {
    const size_t i = static_cast<size_t>(y) * width() + x;
    __builtin_prefetch(&sum_.at(x, y), 1);
    __builtin_prefetch(&samples_[i], 1);
    __builtin_prefetch(&square_sum_[i].r, 1);
    __builtin_prefetch(&square_sum_[i].b, 1);  // a 24-byte sum may cross a line
    for (int h = 0; h < 2; ++h) {
      __builtin_prefetch(&half_sum_[h].at(x, y), 1);
      __builtin_prefetch(&half_samples_[h][i], 1);
    }
  }
  uint32_t samples(int x, int y) const { return samples_[static_cast<size_t>(y) * width() + x]; }
  uint64_t total_samples() const;                                 // over all pixels
  const Color& sum(int x, int y) const { return sum_.at(x, y); }  // of the pixel's samples
  // The half films: samples of even (half 0) and odd (half 1) index.
  uint32_t half_samples(int half, int x, int y) const {
    return half_samples_[half][static_cast<size_t>(y) * width() + x];
  }
  const Color& half_sum(int half, int x, int y) const { return half_sum_[half].at(x, y); }

  // Estimated variance of the pixel's mean, averaged over r, g and b (sample variance / n); 0
  // below 2 samples.
  double variance_of_mean(int x, int y) const;

  // The image's own expected RMSE against its converged limit (r, g, b counted separately, as
  // image/metrics does): sqrt(mean of variance_of_mean). Pixels with < 2 samples count as 0.
  double estimated_rmse() const;

  // Mean over the pixels that have samples of the length sqrt(r^2+g^2+b^2) of their current
  // estimate; 0 when no pixel has one (the scale of a relative firefly clamp).
  double mean_value_length() const;

  // The current estimate (sum / count per pixel).
  Image resolve() const;
  void clear();

 private:
  // The full film's part of an add; `i` is pixel (x, y)'s index.
  void add_full(size_t i, int x, int y, Color radiance_sum, uint32_t count,
                const SquareSum& squares) {
    sum_.at(x, y) += radiance_sum;
    samples_[i] += count;
    square_sum_[i].r += squares.r;
    square_sum_[i].g += squares.g;
    square_sum_[i].b += squares.b;
  }

  Image sum_;
  std::vector<uint32_t> samples_;
  std::vector<SquareSum> square_sum_;
  Image half_sum_[2];
  std::vector<uint32_t> half_samples_[2];
};

}  // namespace tuneray
