#include "render/reuse_switch.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tuneray {

float ReuseMoments::clip_length(double mean_pixel_length) {
  return mean_pixel_length > 0 ? kClip * static_cast<float>(mean_pixel_length)
                               : std::numeric_limits<float>::infinity();
}

namespace {
float clipped_squared_length(Color d, float clip) {
  const float squared = dot(d, d);
  return squared > clip * clip ? clip * clip : squared;
}
}  // namespace

void ReuseMoments::add_sample(const Film& film, int x, int y, Color own_estimate,
                              Color reused_estimate, float clip, ReusePixelMoments* pixels) {
  const uint32_t n = film.samples(x, y);
  if (n == 0) return;
  const Color mean = film.sum(x, y) / static_cast<float>(n);
  const double d_own = clipped_squared_length(own_estimate - mean, clip);
  const double d_reused = clipped_squared_length(reused_estimate - mean, clip);
  const double weight = 1.0 / n;
  own += weight * d_own * n / (n + 1.0);
  removed += weight * (d_own - d_reused);
  weights += weight;
  ++samples;
  if (pixels)
    pixels->add(static_cast<size_t>(y) * static_cast<size_t>(film.width()) + x,
                d_own * n / (n + 1.0), d_own - d_reused);
}

void ReusePixelMoments::resize(size_t pixels) {
  own_.assign(pixels, 0.0f);
  removed_.assign(pixels, 0.0f);
  count_.assign(pixels, 0);
}

namespace {
// Adds the eight lanes of `v` to the four double lanes of `sum` (float sums of a large film's
// deviations would drift by up to a per cent).
void add_to_doubles(__m256d& sum, __m256 v) {
  sum = _mm256_add_pd(sum, _mm256_cvtps_pd(_mm256_castps256_ps128(v)));
  sum = _mm256_add_pd(sum, _mm256_cvtps_pd(_mm256_extractf128_ps(v, 1)));
}
double lane_sum(__m256d v) {
  alignas(32) double lanes[4];
  _mm256_store_pd(lanes, v);
  return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
}
}  // namespace

ReusePixelMoments::Deviations ReusePixelMoments::deviations() const {
  // Eight pixels at a time: it runs at every decision, between passes while the workers wait,
  // and one pixel at a time it took 0.5 ms of a 320x240 film's quarter-second render per call
  // (1.4 % of that render over its seven decisions).
  Deviations d;
  const size_t n = count_.size();
  const __m256 zero = _mm256_setzero_ps();
  __m256d own_sum = _mm256_setzero_pd(), reused_sum = _mm256_setzero_pd();
  size_t p = 0;
  for (; p + 8 <= n; p += 8) {
    const __m256i count = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&count_[p]));
    const __m256 has = _mm256_castsi256_ps(_mm256_cmpgt_epi32(count, _mm256_setzero_si256()));
    // 1/0 is infinite, and the mask makes it 0: pixels without samples add nothing.
    const __m256 inv =
        _mm256_and_ps(has, _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_cvtepi32_ps(count)));
    const __m256 own = _mm256_loadu_ps(&own_[p]);
    const __m256 reused = _mm256_sub_ps(own, _mm256_loadu_ps(&removed_[p]));
    add_to_doubles(own_sum, _mm256_sqrt_ps(_mm256_max_ps(zero, _mm256_mul_ps(own, inv))));
    add_to_doubles(reused_sum, _mm256_sqrt_ps(_mm256_max_ps(zero, _mm256_mul_ps(reused, inv))));
    d.pixels += static_cast<size_t>(__builtin_popcount(_mm256_movemask_ps(has)));
  }
  d.own = lane_sum(own_sum);
  d.reused = lane_sum(reused_sum);
  for (; p < n; ++p) {
    if (count_[p] == 0) continue;
    const float inv = 1.0f / static_cast<float>(count_[p]);
    d.own += std::sqrt(std::max(0.0f, own_[p] * inv));
    d.reused += std::sqrt(std::max(0.0f, (own_[p] - removed_[p]) * inv));
    ++d.pixels;
  }
  return d;
}

void ReuseSwitch::after_reuse_pass(const ReuseMoments& pass, double film_spp,
                                   double pass_cost_ratio, const ReusePixelMoments* pixels) {
  moments_.add(pass);
  const double pools = moments_.cost_ratio();
  if (moments_.samples < kMinSamples || pools <= 0) return;  // undecided: as it is
  if (static_cast<double>(moments_.samples) >=
      kRedecideGrowth * static_cast<double>(decided_samples_)) {
    const double ratio = std::max(pools, pass_cost_ratio);
    double own = moments_.own_variance(), reused = moments_.reused_variance();
    if (pixels) {
      const ReusePixelMoments::Deviations d = pixels->deviations();
      if (d.pixels == 0) return;  // a new view's first pass: its pixels had no mean yet
      own = d.own * d.own;
      reused = d.reused * d.reused;
    }
    on_ = own > 0 && ratio * reused < (1 - kMinGain) * own;
    decided_samples_ = moments_.samples;
  }
  next_probe_spp_ = on_ ? 0 : 2 * film_spp;
}

}  // namespace tuneray
