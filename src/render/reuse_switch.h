// Path reuse switched on where it pays (QualityOptions::path_reuse_auto). Reuse lowers a
// diffuse interior's error at equal time by half and raises a directly lit scene's (its cost,
// 15 shadow rays per path with pools of 16, buys nothing where the noise is in the first hit's
// own light sample; docs/quality.md). Which one a view is, the renderer can measure: a pass with
// reuse gives, for every sample, both the value it adds (the pool's estimate) and the value the
// same random numbers give without reuse (the path's own walk). Both are unbiased estimates of
// the same pixel, so the difference of their second moments about the pixel's mean is the
// variance reuse removes, and the passes' times give what it costs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

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
class ReusePixelMoments;

struct ReuseMoments {
  double own = 0;        // sum of |d_own|^2 n / (n + 1) / n
  double removed = 0;    // sum of (|d_own|^2 - |d_reused|^2) / n
  double weights = 0;    // sum of 1 / n
  uint64_t samples = 0;  // those whose pixel had a sample before
  // What reuse costs, from the same passes: their thread time and the share of it the pools
  // took (their connection rays and gathers). Without reuse a pass would cost the rest, so the
  // passes with reuse tell both costs and no pass without it is needed to compare.
  double traced_ms = 0;
  double pool_ms = 0;
  // Deviations are clipped at this many times the image's mean pixel length.
  static constexpr float kClip = 8;
  // The clip length for an image of this mean pixel length (none for a black one).
  static float clip_length(double mean_pixel_length);
  // One sample of pixel (x, y), before it is added to the film; also to `pixels` when given.
  void add_sample(const Film& film, int x, int y, Color own_estimate, Color reused_estimate,
                  float clip, ReusePixelMoments* pixels = nullptr);
  void add(const ReuseMoments& o) {
    own += o.own;
    removed += o.removed;
    weights += o.weights;
    samples += o.samples;
    traced_ms += o.traced_ms;
    pool_ms += o.pool_ms;
  }
  // Weighted means of the variance of one sample without and with reuse.
  double own_variance() const { return weights > 0 ? own / weights : 0; }
  double reused_variance() const { return weights > 0 ? (own - removed) / weights : 0; }
  // Cost per sample with reuse over without (0 while no time is known).
  double cost_ratio() const {
    return traced_ms > 0 && pool_ms >= 0 && pool_ms < traced_ms ? traced_ms / (traced_ms - pool_ms)
                                                                : 0;
  }
};

// The same sums pixel by pixel (unweighted), for renders with adaptive sampling. There the
// error of a budget is not the mean of the pixels' variances: samples go where the error is
// (n_p proportional to sigma_p), so the squared error of the image, sum sigma_p^2 / n_p, goes as
// (sum sigma_p)^2 over the samples taken. Reuse that lowers the variance of many moderately
// noisy pixels (indirect light on walls) and leaves a few very noisy ones alone (a caustic)
// changes that sum far more than the mean variance: on cornell-box-water it lowers the error
// at equal time by an eighth with adaptive sampling and raises it by as much without
// (docs/quality.md, fifty-first session).
// A pixel is written by one thread per pass (the schedulers' chunks hold whole pixels).
class ReusePixelMoments {
 public:
  explicit ReusePixelMoments(size_t pixels = 0) { resize(pixels); }
  void resize(size_t pixels);
  void add(size_t pixel, double own, double removed) {
    own_[pixel] += static_cast<float>(own);
    removed_[pixel] += static_cast<float>(removed);
    ++count_[pixel];
  }
  // Sums over the pixels with samples of the standard deviation of one sample, without and
  // with reuse (a pixel whose estimate of the latter is negative counts 0).
  struct Deviations {
    double own = 0, reused = 0;
    size_t pixels = 0;
  };
  Deviations deviations() const;

 private:
  std::vector<float> own_, removed_;
  std::vector<uint32_t> count_;
};

// The decision, pass by pass. Reuse pays where it gives the lower error per unit of time: at
// cost c (ms per spp) and variance v per sample the squared error of a time budget goes as
// c x v, so on iff c_on x v_reused < (1 - kMinGain) x c_off x v_own. Every pass with reuse
// measures all four, so reuse is on from the first pass (on a short render the passes spent
// finding out would otherwise be much of its time, and where reuse pays it pays most there).
// It stays on while it pays; once it does not, it is off and is probed again each time the
// film's samples per pixel have doubled (so probes cost a vanishing share of a long render,
// and a decision taken on few samples is revisited).
class ReuseSwitch {
 public:
  // Samples in the moments before a decision is trusted; fewer and the switch stays as it is.
  static constexpr uint64_t kMinSamples = 4096;
  // A decision is taken again once the moments hold this many times the samples of the last
  // one: summing a large image's pixel deviations after every pass would cost a 60 fps frame
  // several milliseconds, and a few more samples hardly move the sums.
  static constexpr double kRedecideGrowth = 1.25;
  // The share of the error per unit of time reuse must save to be switched on: where it changes
  // nothing (no diffuse first hits) the two costs differ by noise alone.
  static constexpr double kMinGain = 0.05;

  // Whether the next pass traces with reuse, the film holding `film_spp` samples per pixel.
  bool next_on(double film_spp) const { return on_ || film_spp >= next_probe_spp_; }
  // True once reuse was found not to pay: a pass with it is a probe, kept small.
  bool probing() const { return !on_; }
  bool on() const { return on_; }

  // After a pass with reuse: its moments and costs, the film's samples per pixel after it and,
  // when known, the cost ratio of whole passes with and without reuse (0 if not). The moments'
  // own ratio counts only the pools' time, so it is a lower bound (on cornell-box-original
  // 1.9 where whole renders take 2.5x): the larger of the two decides. Until the moments hold
  // kMinSamples samples and a time, the switch stays as it is; after a decision, until they
  // hold kRedecideGrowth times as many.
  // With `pixels` (renders with adaptive sampling) the variances compared are the squared sums
  // of the pixels' deviations, (sum sigma_p)^2, else the moments' weighted mean variances.
  void after_reuse_pass(const ReuseMoments& pass, double film_spp, double pass_cost_ratio = 0,
                        const ReusePixelMoments* pixels = nullptr);
  const ReuseMoments& moments() const { return moments_; }

 private:
  ReuseMoments moments_;
  bool on_ = true;
  double next_probe_spp_ = 0;
  uint64_t decided_samples_ = 0;  // the moments' samples at the last decision
};

}  // namespace tuneray
