// The quality ablation behind `tuneray bench quality`: RMSE against a cached ground truth after
// each frame of a frame-budget render, for the baseline, every quality technique alone, the
// unbiased ones together and all together (docs/quality.md).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "bench/ground_truth.h"

namespace tuneray {

struct QualityBenchOptions {
  std::vector<std::string> scenes;  // empty: every scenes/*.json
  int width = 640, height = 360;
  double frame_ms = 250;
  int frames = 8;
  int repeats = 1;        // runs per configuration (seeds differ); the table shows medians
  double target_spp = 0;  // > 0: frame_ms = target_spp x the baseline's measured ms per spp
  int max_bounces = 3;
  std::string truth_dir = "out/truth";
  int truth_spp = 4096;
  double truth_until_rmse = 0;    // > 0: the truth stops once its estimated RMSE is below this
  int bias_spp = 32;              // spp of the common-random-number bias estimate
  float clamp = 0;                // absolute firefly clamp m for the clamp rows (0: relative)
  float clamp_relative = 16;      // m = this x the image's mean pixel length
  std::vector<std::string> only;  // run only these configurations
  bool sweep = false;             // tile size / batch size sweep
  std::string json;
  std::string plot;  // prefix: writes PREFIX.dat and PREFIX.gp
  std::string scenes_dir;
};

// The configuration names, in table order (for --only and the documentation).
std::vector<std::string> quality_configurations();
// Throws std::invalid_argument naming the first unknown name of `only`.
void check_quality_configurations(const std::vector<std::string>& only);

// One frame-budget run of a configuration: cumulative time, spp and RMSE after each frame.
struct FrameRun {
  std::vector<double> time_ms, spp, rmse;
  double mrays_per_s = 0;
};

// A configuration's row: medians over the repeats.
struct QualityRow {
  std::string name;
  std::vector<double> time_ms, spp, rmse;  // after each frame (time and spp cumulative)
  std::vector<double> rmse_repeats;        // final RMSE of each repeat
  double ms_per_spp = 0, intersect = 0, shading = 0, shadow = 0;  // ms per spp
  double mrays_per_s = 0;
  double bias = 0;  // RMSE vs the unbiased render with the same random numbers; 0 if unbiased
  double rmse_at_budget = 0;    // RMSE at exactly frames x frame budget (rmse_at_time)
  double time_over_budget = 0;  // wall time of the frames / (frames x frame budget)
  double baseline_rmse = 0;     // the baseline row's rmse_at_budget, 0 until it has run
  double rmse_vs_baseline() const {
    return baseline_rmse > 0 ? rmse_at_budget / baseline_rmse : 0.0;
  }
  // The truth has noise of its own, independent of the runs', which adds to every measured RMSE
  // in quadrature (image/metrics.h): little to the baseline's, a good share to a row whose error
  // is a few times lower. These are against the exact image: the truth's noise, as its halves
  // estimate it, taken off (QualityScene::truth_noise_rmse).
  double exact_rmse_at_budget = 0;
  double exact_baseline_rmse = 0;
  double exact_rmse_vs_baseline() const {
    return exact_baseline_rmse > 0 ? exact_rmse_at_budget / exact_baseline_rmse : 0.0;
  }
};

// Medians over the repeats, frame by frame, and per-run figures reduced to their medians;
// `budget_ms` is frames x frame budget. Every run has the same number of frames.
QualityRow summarize_runs(const std::string& name, const std::vector<FrameRun>& runs,
                          double budget_ms);

struct SweepPoint {
  std::string mode;  // "tile" or "wavefront"
  int size = 0;      // tile side or batch size
  double ms_per_spp = 0;
};

struct QualityScene {
  std::string spec, name;
  size_t triangles = 0;
  size_t one_texel_candidates = 0, one_texel_collapsed = 0;
  std::string truth_path;
  GroundTruthInfo truth;
  double truth_noise_rmse = 0;  // the truth's own error against the exact image, from its halves
  int truth_spp = 0;            // rendered, or the requested count when read from the cache
  double frame_ms = 0;
  std::vector<QualityRow> rows;
  std::vector<SweepPoint> sweep;
};

// What the caller sees while a scene runs (all optional), in this order: loaded (name, triangles,
// one-texel counts), truth_progress during a truth render, ready (truth and frame budget known),
// repeat_done after every repeat when there are several, row per configuration, sweep per point.
struct QualityHooks {
  std::function<void(const QualityScene&)> loaded;
  TruthProgress truth_progress;
  std::function<void(const QualityScene&)> ready;
  std::function<void(const QualityScene&, int repeat)> repeat_done;
  std::function<void(const QualityRow&)> row;
  std::function<void(const SweepPoint&)> sweep;
};

QualityScene run_quality_scene(const QualityBenchOptions& options, const std::string& spec,
                               const QualityHooks& hooks = {});

}  // namespace tuneray
