// `tuneray tune`: the renderer tuning its BVH online along a camera path. For each camera
// position: compute the indicators, ask the tuner, rebuild the BVH if the configuration changed,
// render, report the cost. Everything goes to the tuning database, so a second run on the same
// database starts with trained predictors.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tuning/frame_bench.h"

namespace tuneray {

struct TuneOptions {
  std::string scene = "cornell";
  std::string scenes_dir;
  Objective objective = Objective::kRender;
  std::string db_path = "tuning.db";
  double epsilon = 0.1;
  std::string predictor = "both";  // nn | rbf | both
  int iterations = 80;             // frames per camera position
  int cameras = 10;                // positions sampled along the path
  int camera_path = 0;             // which path of the scene (automatic when it has none)
  uint32_t spp = 1;
  int width = 320, height = 180;
  int max_bounces = 3;
  uint64_t seed = 1;
  int baseline_repeats = 3;  // side-by-side re-measurements of default and chosen
  // Also tune the scheduler and its work size (tuning/render_space.h), under another tuning key.
  bool work_sizes = false;
  bool progress = true;
};

struct CameraTuneResult {
  int camera = 0;
  std::string mode;  // "search" or "exploit"
  int frames = 0;
  double default_ms = 0;      // median of baseline_repeats, measured beside chosen_ms
  double chosen_ms = 0;       // the configuration the tuner settled on
  double accumulated_ms = 0;  // sum of the costs of all frames at this camera
  std::string config;         // chosen configuration (BVH, then work sizes when tuned)
  bool converged = false;
  double speedup() const { return chosen_ms > 0 ? default_ms / chosen_ms : 0.0; }
};

struct TuneReport {
  std::vector<CameraTuneResult> cameras;
  int failed_builds = 0;
};

struct TuneProgress {
  int camera = 0, frame = 0;  // of this frame
  int frames_done = 0, frames_total = 0;
  double best_speedup = 0;  // default cost / best cost seen so far at this camera
};

// The database namespace of a session: costs are only comparable at the same objective, image
// size, spp, path length and search space, so samples of the space with work sizes are stored
// apart from BVH-only ones.
std::string tuning_key(const TuneOptions& options);

// Runs the loop; `log` receives one line per camera, `on_frame` is called after every frame
// (both may be empty).
TuneReport run_tune_session(const TuneOptions& options,
                            const std::function<void(const std::string&)>& log = {},
                            const std::function<void(const TuneProgress&)>& on_frame = {});

}  // namespace tuneray
