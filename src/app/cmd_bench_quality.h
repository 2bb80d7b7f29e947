// `tuneray bench quality`: RMSE against a cached ground truth after each frame of a frame-budget
// render, for the baseline, every quality technique alone, the unbiased ones together and all
// together (docs/quality.md).
#pragma once

#include <string>
#include <vector>

namespace tuneray {

struct BenchQualityArgs {
  std::vector<std::string> scenes;  // empty: every scenes/*.json
  std::string size = "640x360";
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
std::vector<std::string> bench_quality_configurations();

int run_bench_quality(const BenchQualityArgs& args);

}  // namespace tuneray
