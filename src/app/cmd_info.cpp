// tuneray info SCENE: what a scene holds, how long it took to load, and the 17 indicators the
// tuner sees for each of its cameras.
#include <chrono>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "bench/scene_report.h"
#include "scene/load.h"

namespace tuneray {

namespace {

using Json = nlohmann::ordered_json;

struct InfoArgs {
  std::string scene = "cornell";
  std::string scenes_dir;
  bool json = false;
};

int run_info(const InfoArgs& a) {
  auto start = std::chrono::steady_clock::now();
  LoadOptions options;
  options.scenes_dir = a.scenes_dir;
  Scene scene = load_scene(a.scene, options);
  double load_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  Json j = scene_report_json(scene, a.scene, load_ms);

  if (a.json) {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  for (auto& [key, value] : j.items()) {
    if (key == "indicators" || key == "notes") continue;
    std::cout << key << std::string(20 - key.size(), ' ') << value.dump() << "\n";
  }
  for (const auto& note : scene.notes) std::cout << "note                " << note << "\n";
  if (!scene.cameras.empty()) {
    std::cout << "indicators (camera " << scene.cameras[0].name << "):\n";
    for (auto& [name, value] : j["indicators"][0]["values"].items())
      std::cout << "  " << name << std::string(26 - name.size(), ' ') << value.get<double>()
                << "\n";
  }
  return 0;
}

}  // namespace

CommandAction add_info_command(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd = app.add_subcommand("info", "Print scene statistics and the tuner's indicators");
  cmd->add_option("scene", args->scene, "Built-in name, mesh file or .json scene")
      ->capture_default_str();
  cmd->add_option("--scenes-dir", args->scenes_dir, "Folder to resolve scene files in");
  cmd->add_flag("--json", args->json, "Print JSON");
  return [args] { return run_info(*args); };
}

}  // namespace tuneray
