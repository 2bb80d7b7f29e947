// Sizes of the evaluation study: how many scenes, cameras, search frames and repetitions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tuning/frame_bench.h"

namespace tuneray {

struct EvalProfile {
  std::string name;
  std::vector<std::string> scenes;  // scene specs (built-in names or files)
  std::string scenes_dir;           // where JSON scenes find their meshes
  int cameras = 100;                // positions along each scene's camera path
  int iterations = 80;              // search frames per camera
  int width = 320, height = 180;
  uint32_t spp = 1;
  int max_bounces = 3;
  int repetitions = 15;  // random train/validation splits
  double train_fraction = 0.8;
  // Each camera's comparison (eval_comparison.h): interleaved rounds from the minimum until the
  // 95 % interval of the ratio between any two configurations is within ±compare_target, or
  // the cap. 6 rounds are the fewest whose median has a 95 % order-statistic interval.
  int compare_min_rounds = 6;
  int compare_max_rounds = 30;
  double compare_target = 0.03;
  // Frames of the default configuration measured during each search, evenly spread and not
  // reported to the tuner: the yardstick that calibrates the search's frames to the load of
  // its comparison's window (eval_records.h, CameraRecord::search_window_load).
  int yardsticks = 10;
  std::vector<Objective> objectives = {Objective::kRender, Objective::kTotal};
  uint64_t seed = 1;
  bool wavefront = QualityOptions{}.wavefront;  // the scheduler frames are measured on
  bool native_in_space = true;  // native Embree is a choice of the search (make_backend_space)
  // Each search's first simplex holds the seeds `tune` gives its searches (tuning_seeds: our tree
  // with Embree's BVH8 settings and its variants) in place of its first Latin Hypercube points.
  // Off: the paper's protocol, searches from the default configuration and random points only.
  bool seeded = false;
  // Every measurement replaced by a deterministic made-up cost (tuning/eval_costs.h): for tests
  // of resume and reproducibility only, the figures say nothing about the renderer.
  bool synthetic_costs = false;
};

// "quick": two small built-in scenes, CI-sized (minutes). "standard": every shared scene,
// reduced cameras and iterations (about an hour on 2 cores). "paper": 100 cameras x 80
// iterations on every shared scene. `shared_scenes` are the scene specs of the shared scenes.
// Throws std::invalid_argument for an unknown name.
EvalProfile eval_profile(const std::string& name, const std::vector<std::string>& shared_scenes);

}  // namespace tuneray
