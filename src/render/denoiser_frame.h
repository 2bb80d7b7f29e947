// The image a frame shows: the film's estimate, denoised when the renderer's settings ask for
// it (QualityOptions::denoise). The film is never changed, so it keeps accumulating the
// unbiased estimate and every frame filters the better estimate afresh.
#pragma once

#include <optional>

#include "image/image.h"
#include "render/denoiser.h"
#include "render/denoiser_features.h"
#include "render/film.h"
#include "render/tile_renderer.h"

namespace tuneray {

class FrameResolver {
 public:
  explicit FrameResolver(DenoiseParams params = {}) : params_(params) {}

  // The features are rendered on the first denoised frame and kept.
  Image resolve(const TileRenderer& renderer, const Film& film);
  // Call after TileRenderer::set_camera: the kept features show the old view.
  void camera_moved() { features_.reset(); }

  // Time of the last resolve (features included when they were rendered) in ms.
  double last_ms() const { return last_ms_; }

 private:
  DenoiseParams params_;
  std::optional<DenoiseFeatures> features_;
  double last_ms_ = 0;
};

}  // namespace tuneray
