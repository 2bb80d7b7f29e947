// What `render` writes: images, the JSON report, and the --truth-dir mode's cached reference.
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "app/progress.h"
#include "app/render_args.h"
#include "bench/ground_truth.h"
#include "image/atomic_file.h"
#include "image/io.h"

namespace tuneray {

std::string default_output(const Scene& scene) {
  std::string stem = std::filesystem::path(scene.name.empty() ? "render" : scene.name).stem();
  return "out/" + stem + ".png";
}

void check_output_extensions(const std::vector<std::string>& outputs) {
  for (const std::string& out : outputs) {
    std::string ext = std::filesystem::path(out).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext != ".png" && ext != ".exr" && ext != ".pfm")
      throw std::invalid_argument("cannot write '" + out +
                                  "': unknown image extension (use .png, .exr or .pfm)");
  }
}

void write_outputs(const std::vector<std::string>& outputs, const Image& image, float exposure) {
  WriteOptions write_options;
  write_options.exposure = exposure;
  for (const std::string& out : outputs) {
    std::filesystem::path parent = std::filesystem::path(out).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    write_image(out, image, write_options);
  }
}

void write_report(const std::string& path, const nlohmann::ordered_json& report) {
  if (path.empty()) return;
  std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  write_text_file(path, report.dump(2) + "\n");
}

int run_truth(const RenderArgs& a, int width, int height, const Scene& scene, const Accel& accel,
              double load_ms, double build_ms) {
  GroundTruthKey key{a.scene,     scene.cameras[a.camera], width, height, a.max_bounces, a.spp,
                     a.until_rmse};
  GroundTruthInfo info;
  ProgressBar bar("truth", static_cast<uint64_t>(key.spp), !a.quiet && stderr_is_terminal());
  Image image = ground_truth(a.truth_dir, key, scene, accel, &info, [&](int spp, double estimate) {
    bar.advance(static_cast<uint64_t>(spp));
    if (estimate >= 0) bar.set_suffix("est. RMSE " + std::to_string(estimate));
  });
  bar.finish();
  write_outputs(a.outputs, image, a.exposure);
  std::string path = ground_truth_path(a.truth_dir, key);
  nlohmann::ordered_json report = {{"scene", a.scene},
                                   {"truth", path},
                                   {"rendered", info.rendered},
                                   {"spp", info.spp},
                                   {"estimated_rmse", info.estimated_rmse},
                                   {"load_ms", load_ms},
                                   {"build_ms", build_ms},
                                   {"render_ms", info.render_ms},
                                   {"outputs", a.outputs}};
  write_report(a.report, report);
  if (!a.quiet) {
    if (info.rendered)
      std::cout << "truth     " << path << " (" << info.spp << " spp in "
                << static_cast<int>(info.render_ms) << " ms, estimated RMSE " << info.estimated_rmse
                << ")\n";
    else
      std::cout << "truth     " << path << " (cached)\n";
    for (const auto& out : a.outputs) std::cout << "wrote     " << out << "\n";
  }
  return 0;
}

}  // namespace tuneray
