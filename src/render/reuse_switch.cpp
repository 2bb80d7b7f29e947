#include "render/reuse_switch.h"

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

ReusePixelMoments::Deviations ReusePixelMoments::deviations() const {
  Deviations d;
  for (size_t p = 0; p < count_.size(); ++p) {
    if (count_[p] == 0) continue;
    const double own = own_[p] / count_[p], reused = (own_[p] - removed_[p]) / count_[p];
    d.own += std::sqrt(std::max(0.0, own));
    d.reused += std::sqrt(std::max(0.0, reused));
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
