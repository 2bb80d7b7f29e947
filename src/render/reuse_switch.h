// Path reuse switched on where it pays (QualityOptions::path_reuse_auto). Reuse lowers a
// diffuse interior's error at equal time by half and raises a directly lit scene's (its cost,
// 15 shadow rays per path with pools of 16, buys nothing where the noise is in the first hit's
// own light sample; docs/quality.md). Which one a view is, the renderer can measure: a pass with
// reuse gives, for every sample, both the value it adds (the pool's estimate) and the value the
// same random numbers give without reuse (the path's own walk). Both are unbiased estimates of
// the same pixel, so the difference of their second moments is the variance reuse removes, and
// the passes' times give what it costs.
#pragma once

#include <cstdint>

namespace tuneray {

// Sums over the samples of passes traced with reuse, r, g and b added as the RMSE adds them:
// own2 of |own|^2, reused2 of |reused|^2 and cross of own . m, m the pixel's mean before the
// sample (from earlier samples, so independent of it: E[own . m] = |mu|^2). Per sample,
// E[|own|^2] - |mu|^2 is the variance of a sample without reuse, E[|reused|^2] - |mu|^2 with it.
struct ReuseMoments {
  double own2 = 0, reused2 = 0, cross = 0;
  uint64_t samples = 0;  // those whose pixel had a sample before
  void add(const ReuseMoments& o) {
    own2 += o.own2;
    reused2 += o.reused2;
    cross += o.cross;
    samples += o.samples;
  }
  double own_variance() const { return samples ? (own2 - cross) / static_cast<double>(samples) : 0; }
  double reused_variance() const {
    return samples ? (reused2 - cross) / static_cast<double>(samples) : 0;
  }
};

// The decision, pass by pass. Reuse pays where it gives the lower error per unit of time: at
// cost c (ms per spp) and variance v per sample the squared error of a time budget goes as
// c x v, so on iff c_on x v_reused < (1 - kMinGain) x c_off x v_own. It needs both costs, so passes run without reuse first;
// from a film with a sample per pixel on, a probe pass runs with it. Then reuse stays on while
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
