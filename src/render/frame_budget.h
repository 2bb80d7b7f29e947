// Frame-budget rendering, as a progressive viewer does it: every frame adds as many samples per
// pixel as fit in `frame_ms`, judged from the measured time per sample of earlier passes, and
// the film keeps accumulating across frames. With quality.path_reuse_auto it also decides, pass
// by pass, whether path reuse pays (render/reuse_switch.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "render/film.h"
#include "render/reuse_switch.h"
#include "render/tile_renderer.h"

namespace tuneray {

struct FrameResult {
  double ms = 0;    // wall time of the frame (rendering + adaptive bookkeeping)
  double spp = 0;   // samples added per pixel (average over pixels when adaptive)
  PassStats stats;  // summed over the frame's passes
};

class FrameBudgetRenderer {
 public:
  // Switches `renderer`'s path reuse (TileRenderer::set_path_reuse) when its settings ask for
  // the automatic choice; leaves it alone otherwise.
  // `reuse`: the path-reuse switch to start from, e.g. the one of the same scene's previous
  // view (what pays depends on the scene far more than on the camera; the viewer keeps it across
  // camera moves, so a moving camera is not traced with reuse where it was found not to pay).
  FrameBudgetRenderer(TileRenderer& renderer, double frame_ms,
                      const ReuseSwitch& reuse = ReuseSwitch{});
  ~FrameBudgetRenderer();
  // The renderer writes into this object's per-pixel reuse moments while it lives.
  FrameBudgetRenderer(const FrameBudgetRenderer&) = delete;
  FrameBudgetRenderer& operator=(const FrameBudgetRenderer&) = delete;

  // `reserved_ms`: the time the caller will spend on the frame after rendering it (the
  // denoiser's filtering, FrameResolver::expected_ms); the passes plan to end that much before
  // the budget, so the shown frame holds it. Every frame still gets one pass.
  FrameResult render_frame(Film& film, double reserved_ms = 0);
  // Running estimate of rendering time per spp of the passes to come (adaptive ones once
  // adaptive sampling has started); 0 = not measured yet.
  double ms_per_spp() const;
  // The automatic path-reuse choice (meaningful when reuse_auto()).
  bool reuse_auto() const { return reuse_auto_; }
  const ReuseSwitch& reuse_switch() const { return reuse_switch_; }

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
  // A path-reuse probe (ReuseSwitch::probing) adds at most this many samples per pixel: where
  // reuse does not pay, probes are what it costs. Before its cost per sample is known, a pass
  // with reuse is planned at this many times the cost without (pools of 16 cost 1.4-1.9x).
  static constexpr double kReuseProbePass = 1.0;
  static constexpr double kReuseCostGuess = 2.0;

  // Uniform and adaptive passes cost differently per sample and are estimated apart.
  struct PassCost {
    double ms_per_spp = 0;   // rendering time per spp; 0 = not measured yet
    double overhead_ms = 0;  // a pass's time outside rendering (adaptive bookkeeping)
    void update(double per_spp, double overhead);
  };

  // Cost of the next pass's kind: [adaptive][with path reuse].
  PassCost& cost(bool adaptive, bool reuse) { return costs_[adaptive][reuse]; }
  const PassCost& cost(bool adaptive, bool reuse) const { return costs_[adaptive][reuse]; }
  // Cost per spp with reuse over without, from passes with and without it: the phase given if
  // both are known there, else the other phase; 0 while unknown.
  double pass_cost_ratio(bool adaptive) const;
  // The larger of that and the share of their time the pools took in passes with reuse
  // (ReuseMoments::cost_ratio, which leaves out what recording the vertices costs); 0 while
  // neither is known.
  double reuse_cost_ratio(bool adaptive) const;
  // The samples per pixel a pass of this kind may add in what is left of the frame.
  double plan_pass(bool adaptive, bool reuse, double left_ms) const;

  TileRenderer& renderer_;
  double frame_ms_;
  PassCost costs_[2][2];
  bool reuse_auto_ = false;
  ReuseSwitch reuse_switch_;
  ReusePixelMoments reuse_pixels_;  // with adaptive sampling (ReuseSwitch::after_reuse_pass)
  uint64_t film_samples_ = 0;       // added by this renderer's passes
  // Samples every pixel has from uniform passes (whole ones, or completed rounds of partial
  // ones): the sample index of the next whole pass, and what adaptive sampling waits for.
  uint32_t uniform_samples_ = 0;
  size_t partial_cursor_ = 0;  // first pixel of the next partial pass; 0 = film uniform
};

}  // namespace tuneray
