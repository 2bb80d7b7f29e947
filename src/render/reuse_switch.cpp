#include "render/reuse_switch.h"

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
                              Color reused_estimate, float clip) {
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
}

void ReuseSwitch::after_reuse_pass(const ReuseMoments& pass, double film_spp, double cost_ratio) {
  moments_.add(pass);
  if (moments_.samples < kMinSamples || cost_ratio <= 0) {
    on_ = false;  // undecided: the next pass probes again
    next_probe_spp_ = 0;
    return;
  }
  const double own = moments_.own_variance();
  on_ = own > 0 && cost_ratio * moments_.reused_variance() < (1 - kMinGain) * own;
  next_probe_spp_ = on_ ? 0 : 2 * film_spp;
}

}  // namespace tuneray
