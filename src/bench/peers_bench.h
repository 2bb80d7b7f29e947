// `tuneray bench peers`: error at equal time against Embree's tutorial path tracer. Both
// programs render Embree's Cornell box at the same size and path length, each against its own
// cached converged reference; the pathtracer's frames are timed with its --benchmark mode, ours
// are frame-budget frames of the default renderer. RMSE is compared at fixed render times.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "bench/embree_peer.h"
#include "render/render_settings.h"

namespace tuneray {

struct PeersBenchOptions {
  EmbreePeer peer;  // binary, scene, size and path length
  std::vector<double> times_s = {0.25, 0.5, 1, 2};
  int reference_spp = 4096;             // both references
  int repeats = 3;                      // timing repeats, interleaved; medians reported
  int timing_frames = 2;                // pathtracer frames per --benchmark run
  double frame_ms = 50;                 // our frame budget
  std::string accel = "native";         // our backend (the render command's default)
  std::string bvh;                      // its parameters, as `render --bvh` takes them
  std::string truth_dir = "out/truth";  // cache of both references
  bool denoise = true;                  // also our runs with the denoiser on
  // Also our runs with the radiance cache (vertex 0: not run).
  RadianceCacheOptions cache = {.vertex = 1};
  // Also our runs with path reuse in pools of this many pixels (0: not run; unbiased).
  int path_reuse = 16;
  bool path_reuse_auto = false;  // ... switched per pass (QualityOptions::path_reuse_auto)
};

// Throws std::invalid_argument naming the first option out of range.
void check_peers_options(const PeersBenchOptions& options);

// The pathtracer's points: samples per pixel of a frame, its render time, its RMSE.
struct PeerPoint {
  int spp = 0;
  double frame_ms = 0;  // median over repeats
  double rmse = 0;      // of its 8-bit output against the truth, estimated from its reference
};

// One of our columns at one time. Our reference has noise of its own, independent of our runs'
// (its own seed and sampler), so our RMSE against it reads sqrt(rmse^2 + its mean squared error)
// against the truth: hardly more than the truth for a raw frame, but for a denoised frame, whose
// error is far below a raw frame's, the reference's noise can be most of what is measured. The
// pathtracer's error is measured against its truth (peer_rmse_against_truth); ours is too, by
// removing the reference's noise as its halves estimate it (image/metrics.h). Both are kept.
struct OurError {
  double measured = 0;  // RMSE against our reference; 0 when the column was not run
  double truth = 0;     // the same without the reference's own noise
};

struct PeersRow {
  double time_s = 0;
  double embree_rmse = 0;
  double ours_spp = 0;  // samples per pixel we had at that time (median)
  OurError raw;         // our linear image against our linear reference
  OurError ldr;         // both passed through the pathtracer's output transform
  // The same with the denoiser on (its filtering counted as frame time).
  OurError denoised, denoised_ldr;
  // The same with the radiance cache on (biased, like the denoiser).
  OurError cached, cached_ldr;
  // The same with path reuse on (QualityOptions::path_reuse; unbiased).
  OurError reused, reused_ldr;
  // Against the truth, as the pathtracer's error is: the comparison the targets are judged by.
  double ratio(const OurError& ours) const { return ours.truth / embree_rmse; }
  // Against our reference as measured (higher: the reference's noise included).
  double measured_ratio(const OurError& ours) const { return ours.measured / embree_rmse; }
};

struct PeersResult {
  bool skipped = false;
  std::string reason;                            // why it was skipped
  std::string embree_reference, ours_reference;  // cache files
  std::vector<PeerPoint> embree;
  double ours_ms_per_spp = 0;  // median over repeats, over the whole run
  // Our reference's own noise as RMSE against the truth (linear, and through the pathtracer's
  // output transform), from its halves.
  double reference_noise_rmse = 0, reference_noise_rmse_ldr = 0;
  std::vector<PeersRow> rows;
};

// Progress lines for long steps (references, repeats); the library prints nothing itself.
using PeersProgress = std::function<void(const std::string&)>;

PeersResult run_peers_bench(const PeersBenchOptions& options, const PeersProgress& progress = {});

// The pathtracer seeds sample i of a pixel by (pixel, i) alone, so an n-spp frame is the mean of
// the first n of its N-spp reference's samples: the two share noise and their difference
// underestimates the frame's error. For independent samples E|mean_n - mean_N|^2 =
// s^2 (1/n - 1/N) while the error against the truth is s^2/n, so this divides by sqrt(1 - n/N).
// Our runs use a seed of their own: their error has the reference's noise added instead
// (OurError). Throws for n >= N.
double peer_rmse_against_truth(double rmse_against_reference, int spp, int reference_spp);

// Where the pathtracer's reference is cached for these options.
std::string embree_reference_path(const PeersBenchOptions& options);

}  // namespace tuneray
