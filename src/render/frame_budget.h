// Frame-budget rendering, as a progressive viewer does it: every frame adds as many samples per
// pixel as fit in `frame_ms`, judged from the measured time per sample of earlier passes, and
// the film keeps accumulating across frames.
#pragma once

#include <cstdint>

#include "render/film.h"
#include "render/tile_renderer.h"

namespace tuneray {

struct FrameResult {
  double ms = 0;    // wall time of the frame (rendering + adaptive bookkeeping)
  double spp = 0;   // samples added per pixel (average over pixels when adaptive)
  PassStats stats;  // summed over the frame's passes
};

class FrameBudgetRenderer {
 public:
  FrameBudgetRenderer(const TileRenderer& renderer, double frame_ms)
      : renderer_(renderer), frame_ms_(frame_ms) {}

  FrameResult render_frame(Film& film);
  double ms_per_spp() const { return ms_per_spp_; }

 private:
  // True once every pixel has the uniform samples adaptive sampling starts from.
  bool adaptive_ready() const;
  // Adds `spp` samples per pixel on average: uniform passes round down to whole samples (at
  // least 1); adaptive passes place round(spp x pixels) samples where the error is highest.
  PassStats add_samples(Film& film, double spp);

  // Below this many samples per pixel an adaptive pass is not worth its bookkeeping.
  static constexpr double kSmallestAdaptivePass = 0.1;

  const TileRenderer& renderer_;
  double frame_ms_;
  double ms_per_spp_ = 0;   // running estimate of rendering time per spp; 0 = not measured yet
  double overhead_ms_ = 0;  // running estimate of a pass's time outside rendering
  int passes_ = 0;
  uint32_t next_sample_ = 0;  // uniform mode: sample index of the next pass
  uint32_t min_samples_ = 0;  // adaptive mode: samples every pixel has
};

}  // namespace tuneray
