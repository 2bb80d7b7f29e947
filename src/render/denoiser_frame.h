// The image a frame shows: the film's estimate, denoised when the renderer's settings ask for
// it (QualityOptions::denoise), each pixel to the strength its half films choose
// (render/denoiser_selection.h). The film is never changed, so it keeps accumulating the
// unbiased estimate and every frame filters the better estimate afresh.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "image/image.h"
#include "render/denoiser.h"
#include "render/denoiser_features.h"
#include "render/denoiser_selection.h"
#include "render/film.h"
#include "render/tile_renderer.h"

namespace tuneray {

class FrameResolver {
 public:
  explicit FrameResolver(DenoiseParams params = {}, SelectionParams selection = {})
      : params_(params), selection_(selection) {}

  // The features are rendered on the first denoised frame and kept.
  Image resolve(const TileRenderer& renderer, const Film& film);
  // Call after TileRenderer::set_camera: the kept features and strengths show the old view.
  void camera_moved() {
    features_.reset();
    feature_rays_per_side_ = 0;
    guide_weights_.reset();
    choice_.clear();
  }

  // Time of the last resolve (features included when they were rendered) in ms.
  double last_ms() const { return last_ms_; }
  // What the next resolve is expected to take, for a frame budget to set aside (0 before the
  // first): a running mean of the resolves without the guides' one-off work, so the frames that
  // renew the strength choice (about 2.5 filterings) are spread over the others.
  double expected_ms() const { return expected_ms_; }

 private:
  DenoiseParams params_;
  SelectionParams selection_;
  std::optional<DenoiseFeatures> features_;
  // The features start from kFirstFeatureRaysPerSide rays a pixel side and are rendered again
  // from kFeatureRaysPerSide once the film has this many samples per pixel on average: by then
  // the coarse guides' error shows beside the noise, and the finer ones' cost is a smaller share
  // of the time spent (docs/quality.md, "Twenty-sixth session").
  static constexpr double kFineFeaturesSpp = 16;
  int feature_rays_per_side_ = 0;
  // The guides' weights, computed with the features for every frame of the view unless they
  // would take more memory than this (then each filtering computes its own).
  static constexpr size_t kMaxGuideWeightBytes = size_t{640} << 20;
  std::optional<GuideWeights> guide_weights_;
  // The per-pixel strengths the halves chose, and the film's sample count then. Filtering both
  // halves costs twice the frame's own filtering, and the choice changes slowly with the
  // samples, so it is renewed only once the film has kReselectGrowth times the samples (1.5
  // until the twenty-sixth session; 2 won at equal time in `bench quality`, docs/quality.md).
  static constexpr double kReselectGrowth = 2.0;
  // Below this many samples per pixel on average the strongest filter is used: at 2 spp each
  // half has one sample per pixel.
  static constexpr double kFirstChoiceSpp = 2;
  std::vector<uint8_t> choice_;
  uint64_t chosen_at_samples_ = 0;
  double last_ms_ = 0;
  double expected_ms_ = 0;
  // The running mean's weight of the newest resolve.
  static constexpr double kExpectedWeight = 0.25;
};

}  // namespace tuneray
