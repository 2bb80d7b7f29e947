#include "render/denoiser_frame.h"

#include <algorithm>
#include <chrono>

#include "render/denoiser_selection.h"

namespace tuneray {

Image FrameResolver::resolve(const TileRenderer& renderer, const Film& film) {
  auto ms_since = [](std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  };
  const auto start = std::chrono::steady_clock::now();
  double one_off_ms = 0;
  Image image;
  if (renderer.settings().quality.denoise) {
    const uint64_t samples = film.total_samples();
    const double pixels = static_cast<double>(film.width()) * film.height();
    const int rays_per_side = static_cast<double>(samples) >= kFineFeaturesSpp * pixels
                                  ? kFeatureRaysPerSide
                                  : kFirstFeatureRaysPerSide;
    if (!features_ || rays_per_side > feature_rays_per_side_) {
      const auto guides_start = std::chrono::steady_clock::now();
      // Finer guides only where the coarse ones' rays disagreed.
      features_ =
          render_denoise_features(renderer, rays_per_side, features_ ? &*features_ : nullptr);
      feature_rays_per_side_ = rays_per_side;
      guide_weights_.reset();
      if (GuideWeights::bytes_for(film.width(), film.height(), params_.iterations) <=
          kMaxGuideWeightBytes)
        guide_weights_.emplace(*features_, params_);
      choice_.clear();  // chosen with the old guides
      one_off_ms = ms_since(guides_start);
    }
    const GuideWeights* guides = guide_weights_ ? &*guide_weights_ : nullptr;
    if (static_cast<double>(samples) < kFirstChoiceSpp * pixels) {
      // Too few pixels have samples in both halves for a choice; the strongest is what the
      // choice gives where no pixel of the window has both.
      choice_.clear();
      image = denoise(noisy_image(film), *features_, params_, guides);
    } else {
      if (choice_.empty() || samples < chosen_at_samples_ ||
          static_cast<double>(samples) >=
              kReselectGrowth * static_cast<double>(chosen_at_samples_)) {
        choice_ = choose_strength(noisy_half_image(film, 0), noisy_half_image(film, 1), *features_,
                                  params_, selection_, guides);
        chosen_at_samples_ = samples;
      }
      image = denoise_chosen(noisy_image(film), *features_, params_, choice_, guides);
    }
  } else {
    image = film.resolve();
  }
  last_ms_ = ms_since(start);
  const double showing_ms = std::max(0.0, last_ms_ - one_off_ms);
  expected_ms_ = expected_ms_ > 0
                     ? (1 - kExpectedWeight) * expected_ms_ + kExpectedWeight * showing_ms
                     : showing_ms;
  return image;
}

}  // namespace tuneray
