// Path reuse switched on where it pays (QualityOptions::path_reuse_auto). Reuse lowers a
// diffuse interior's error at equal time by half and raises a directly lit scene's (its cost,
// 15 shadow rays per path with pools of 16, buys nothing where the noise is in the first hit's
// own light sample; docs/quality.md). Which one a view is, the renderer can measure: a pass with
// reuse gives, for every sample, both the value it adds (the pool's estimate) and the value the
// same random numbers give without reuse (the path's own walk). Both are unbiased estimates of
// the same pixel, so the difference of their second moments about the pixel's mean is the
// variance reuse removes, and the passes' times give what it costs.
#pragma once

#include <cstdint>

#include "math/vec.h"
#include "render/film.h"

namespace tuneray {

// What the samples of passes traced with reuse tell of its worth, r, g and b added as the RMSE
// adds them. Each sample's own estimate and reused one are compared by their deviations d from
// the pixel's mean m of earlier samples (independent of both): E|d|^2 = v + Var(m), so the
// difference of the two estimates' E|d|^2 is exactly the variance reuse removes, and
// E|d_own|^2 n / (n + 1), n earlier samples, estimates v_own (taking Var(m) as v_own / n).
// Deviations are clipped at `clip` (a few times the image's mean pixel length): what both
// estimates share and reuse cannot touch, a light's rim seen directly or a light sample's 1/r^2
// near the light, would otherwise be nearly all of both variances (on the Cornell box 90 % of
// them) and hide what reuse removes from the rest of the image.
//
// Each sample is weighted by 1 / n: an image's squared error is the sum over pixels of v / n,
// and adaptive sampling gives the pixels of high variance (a light's rim, seen directly, whose
// variance no reuse touches) many samples, so per sample they matter less than their variance
// says.
struct ReuseMoments {
  double own = 0;        // sum of |d_own|^2 n / (n + 1) / n
  double removed = 0;    // sum of (|d_own|^2 - |d_reused|^2) / n
  double weights = 0;    // sum of 1 / n
  uint64_t samples = 0;  // those whose pixel had a sample before
  // Deviations are clipped at this many times the image's mean pixel length.
  static constexpr float kClip = 8;
  // The clip length for an image of this mean pixel length (none for a black one).
  static float clip_length(double mean_pixel_length);
  // One sample of pixel (x, y), before it is added to the film.
  void add_sample(const Film& film, int x, int y, Color own_estimate, Color reused_estimate,
                  float clip);
  void add(const ReuseMoments& o) {
    own += o.own;
    removed += o.removed;
    weights += o.weights;
    samples += o.samples;
  }
  // Weighted means of the variance of one sample without and with reuse.
  double own_variance() const { return weights > 0 ? own / weights : 0; }
  double reused_variance() const { return weights > 0 ? (own - removed) / weights : 0; }
};

// The decision, pass by pass. Reuse pays where it gives the lower error per unit of time: at
// cost c (ms per spp) and variance v per sample the squared error of a time budget goes as
// c x v, so on iff c_on x v_reused < (1 - kMinGain) x c_off x v_own. It needs both costs, so
// passes run without reuse first; from a film with a sample per pixel on, a probe pass runs with
// it. Then reuse stays on while
// it pays (each of its passes adds moments); once it does not, it is off and is probed again
// each time the film's samples per pixel have doubled (so probes cost a vanishing share of a
// long render, and a decision taken on few samples is revisited).
class ReuseSwitch {
 public:
  // Samples in the moments before a decision is trusted; fewer and the next pass probes again.
  static constexpr uint64_t kMinSamples = 4096;
  // The share of the error per unit of time reuse must save to be switched on: where it changes
  // nothing (no diffuse first hits) the two costs differ by noise alone.
  static constexpr double kMinGain = 0.05;

  // Whether the next pass traces with reuse, the film holding `film_spp` samples per pixel.
  bool next_on(double film_spp) const { return on_ || film_spp >= next_probe_spp_; }
  // True while reuse is not (yet) found to pay: a pass with it is a probe, kept small.
  bool probing() const { return !on_; }
  bool on() const { return on_; }

  // After a pass with reuse: its moments, the film's samples per pixel after it and the ratio of
  // the costs per spp with and without reuse (0 while either is unknown).
  void after_reuse_pass(const ReuseMoments& pass, double film_spp, double cost_ratio);
  const ReuseMoments& moments() const { return moments_; }

 private:
  ReuseMoments moments_;
  bool on_ = false;
  double next_probe_spp_ = 1;
};

}  // namespace tuneray
