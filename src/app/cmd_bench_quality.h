// `tuneray bench quality`: RMSE against a cached ground truth after each frame of a frame-budget
// render, for the baseline, every quality technique alone and all together (docs/quality.md).
#pragma once

#include <string>
#include <vector>

namespace tuneray {

struct BenchQualityArgs {
  std::vector<std::string> scenes;  // empty: every scenes/*.json
  std::string size = "640x360";
  double frame_ms = 250;
  int frames = 8;
  double target_spp = 0;  // > 0: frame_ms = target_spp x the baseline's measured ms per spp
  int max_bounces = 3;
  std::string truth_dir = "out/truth";
  int truth_spp = 4096;
  int bias_spp = 32;              // spp of the common-random-number bias estimate
  float clamp = 10;               // m for the firefly clamp
  std::vector<std::string> only;  // run only these configurations
  bool sweep = false;             // tile size / batch size sweep
  std::string json;
  std::string plot;  // prefix: writes PREFIX.dat and PREFIX.gp
  std::string scenes_dir;
};

int run_bench_quality(const BenchQualityArgs& args);

}  // namespace tuneray
