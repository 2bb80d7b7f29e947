// Progressive accumulation: a running sum of radiance and a sample count per pixel.
#pragma once

#include <algorithm>
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

class Film {
 public:
  // Upper bound of a render's memory per pixel: the film (squares and two half films),
  // the resolved image and its file encoding, the schedulers' and adaptive sampling's
  // per-pixel arrays.
  static constexpr uint64_t kBytesPerPixelBound = 160;

  Film(int width, int height)
      : width_(std::max(0, width)),
        height_(std::max(0, height)),
        pixels_(static_cast<size_t>(width_) * height_) {}

  int width() const { return width_; }
  int height() const { return height_; }

  // Single writer per pixel (tiles do not overlap), so no synchronisation. `squares` sums the
  // samples' squared channels (variance estimates for adaptive sampling and error estimates).
  // Samples given without their indices all go to the half of the pixel's sample count's
  // parity, so one-sample adds alternate between the halves as the schedulers' indices do.
  void add(int x, int y, Color radiance_sum, uint32_t count, const SquareSum& squares = {}) {
    Pixel& p = pixel(x, y);
    const int half = p.samples() & 1;
    p.add_squares(squares);
    p.half_sum[half] += radiance_sum;
    p.half_samples[half] += count;
  }
  // One sample of index `index`. The film keeps two half films, of the even and of the odd
  // sample indices: independent estimates of the same pixel that let the denoiser measure its
  // own error (render/denoiser_selection.h). The index's parity picks the half.
  void add_sample(int x, int y, Color radiance, uint32_t index) {
    Pixel& p = pixel(x, y);
    p.squares.add(radiance);
    p.half_sum[index & 1] += radiance;
    ++p.half_samples[index & 1];
  }
  // Asks for pixel (x, y)'s record ahead of an add: the schedulers add pixels in blocks
  // (wave_pixel_order.h), whose rows are too short for the hardware's stream prefetchers, and
  // a 640×360 film is larger than the caches. A record is one cache line. Always inlined: GCC 12
  // finds an out-of-line copy free of side effects and deletes its calls.
  [[gnu::always_inline]] void prefetch(int x, int y) const { __builtin_prefetch(&pixel(x, y), 1); }
  uint32_t samples(int x, int y) const { return pixel(x, y).samples(); }
  uint64_t total_samples() const;                              // over all pixels
  Color sum(int x, int y) const { return pixel(x, y).sum(); }  // of the pixel's samples
  // The half films: samples of even (half 0) and odd (half 1) index.
  uint32_t half_samples(int half, int x, int y) const { return pixel(x, y).half_samples[half]; }
  const Color& half_sum(int half, int x, int y) const { return pixel(x, y).half_sum[half]; }

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
  // One half film's estimate (0: even sample indices, 1: odd); black where it has no samples.
  // Throws std::invalid_argument for another half.
  Image resolve_half(int half) const;
  void clear();

 private:
  // Everything an add writes for one pixel in one cache line: an add at one sample per pixel
  // touches one line. The full film's sum and count are its halves' (even and odd sample
  // indices), so they are not stored apart.
  struct alignas(64) Pixel {
    SquareSum squares;
    Color half_sum[2] = {Color(0.0f), Color(0.0f)};
    uint32_t half_samples[2] = {0, 0};
    Color sum() const { return half_sum[0] + half_sum[1]; }
    uint32_t samples() const { return half_samples[0] + half_samples[1]; }
    void add_squares(const SquareSum& s) {
      squares.r += s.r;
      squares.g += s.g;
      squares.b += s.b;
    }
  };
  static_assert(sizeof(Pixel) == 64);
  Pixel& pixel(int x, int y) { return pixels_[static_cast<size_t>(y) * width_ + x]; }
  const Pixel& pixel(int x, int y) const { return pixels_[static_cast<size_t>(y) * width_ + x]; }
  // Each pixel's sum / count, as `part(pixel)` gives them (black without samples), on all cores:
  // every shown frame resolves the whole film. Defined in film.cpp, its only user.
  template <typename Part>
  Image resolve_each(Part part) const;

  int width_, height_;
  std::vector<Pixel> pixels_;
};

}  // namespace tuneray
