// Frame-budget rendering, as a progressive viewer does it: every frame adds as many samples per
// pixel as fit in `frame_ms`, judged from the measured time per sample of earlier passes, and
// the film keeps accumulating across frames.
#pragma once

#include <cstddef>
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

  // `reserved_ms`: the time the caller will spend on the frame after rendering it (the
  // denoiser's filtering, FrameResolver::expected_ms); the passes plan to end that much before
  // the budget, so the shown frame holds it. Every frame still gets one pass.
  FrameResult render_frame(Film& film, double reserved_ms = 0);
  // Running estimate of rendering time per spp of the passes to come (adaptive ones once
  // adaptive sampling has started); 0 = not measured yet.
  double ms_per_spp() const;

 private:
  // True once every pixel has the uniform samples adaptive sampling starts from.
  bool adaptive_ready() const;
  // Adds `spp` samples per pixel on average: uniform passes of at least one sample round down
  // to whole samples, smaller ones give one sample to the next round(spp x pixels) pixels in
  // row order (a partial pass), finishing the round before whole passes resume; adaptive passes
  // place round(spp x pixels) samples where the error is highest.
  PassStats add_samples(Film& film, double spp);
  PassStats add_partial_pass(Film& film, double spp);

  // Below this many samples per pixel a pass is not worth its set-up and bookkeeping.
  static constexpr double kSmallestPass = 0.1;
  // The very first pass, before any cost is known: small enough that a 60 fps budget holds
  // on small scenes.
  static constexpr double kFirstPass = 0.25;
  // The first adaptive pass, before its cost per sample is known: adaptive samples go where
  // the error is, which is where paths are long (often 2-5x a uniform sample), so planning
  // it with the uniform cost would overrun the frame.
  static constexpr double kAdaptiveProbePass = 0.25;

  // Uniform and adaptive passes cost differently per sample and are estimated apart.
  struct PassCost {
    double ms_per_spp = 0;   // rendering time per spp; 0 = not measured yet
    double overhead_ms = 0;  // a pass's time outside rendering (adaptive bookkeeping)
    void update(double per_spp, double overhead);
  };

  const TileRenderer& renderer_;
  double frame_ms_;
  PassCost uniform_cost_, adaptive_cost_;
  // Samples every pixel has from uniform passes (whole ones, or completed rounds of partial
  // ones): the sample index of the next whole pass, and what adaptive sampling waits for.
  uint32_t uniform_samples_ = 0;
  size_t partial_cursor_ = 0;  // first pixel of the next partial pass; 0 = film uniform
};

}  // namespace tuneray
