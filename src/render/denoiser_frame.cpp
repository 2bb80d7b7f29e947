#include "render/denoiser_frame.h"

#include <chrono>

namespace tuneray {

Image FrameResolver::resolve(const TileRenderer& renderer, const Film& film) {
  auto start = std::chrono::steady_clock::now();
  Image image;
  if (renderer.settings().quality.denoise) {
    if (!features_) features_ = render_denoise_features(renderer);
    image = denoise(noisy_image(film), *features_, params_);
  } else {
    image = film.resolve();
  }
  last_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return image;
}

}  // namespace tuneray
