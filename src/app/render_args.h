// `tuneray render`: its options (cmd_render_cli.cpp registers them), the run (cmd_render.cpp)
// and the image and report outputs it shares with the --truth-dir mode (render_output.cpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "app/quality_cli.h"
#include "image/image.h"
#include "scene/scene.h"

namespace tuneray {

struct RenderArgs {
  std::string scene = "cornell";
  int spp = 16;
  std::string size = "640x360";
  std::vector<std::string> outputs;
  std::string accel = "native";
  std::string bvh;
  int threads = 0;
  uint64_t seed = 0;
  int max_bounces = 3;
  int camera = 0;
  int tile_size = 32;
  std::string strategy = "mis";
  std::string report;
  std::string scenes_dir;
  float exposure = 0;
  bool quiet = false;
  bool profile_phases = false;  // time intersection, shading and shadow rays apart
  double frame_ms = 0;          // > 0: frame-budget mode
  int frames = 1;
  double until_rmse = 0;  // > 0: stop once the image's estimated RMSE is below this
  std::string truth_dir;  // non-empty: render (or read) the cached ground truth
  QualityCli quality;
};

// Samples per pixel of a ground truth when --spp is not given (docs/quality.md).
constexpr int kTruthSpp = 4096;

int run_render(const RenderArgs& args);

// --truth-dir: the ground truth of `bench quality` (same cache, same key), read or rendered.
int run_truth(const RenderArgs& args, int width, int height, const Scene& scene, const Accel& accel,
              double load_ms, double build_ms);

std::string default_output(const Scene& scene);
// Checked before rendering so a typo does not cost a long render.
void check_output_extensions(const std::vector<std::string>& outputs);
void write_outputs(const std::vector<std::string>& outputs, const Image& image, float exposure);
void write_report(const std::string& path, const nlohmann::ordered_json& report);

}  // namespace tuneray
