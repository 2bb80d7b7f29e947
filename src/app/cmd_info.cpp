// tuneray info SCENE: what a scene holds, how long it took to load, and the 17 indicators the
// tuner sees for each of its cameras.
#include <chrono>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "scene/indicators.h"
#include "scene/load.h"
#include "scene/one_texel.h"
#include "scene/stats.h"

namespace tuneray {

namespace {

using Json = nlohmann::ordered_json;

struct InfoArgs {
  std::string scene = "cornell";
  std::string scenes_dir;
  bool json = false;
};

Json vec_json(Vec3f v) {
  return {v.x, v.y, v.z};
}

int run_info(const InfoArgs& a) {
  auto start = std::chrono::steady_clock::now();
  LoadOptions options;
  options.scenes_dir = a.scenes_dir;
  Scene scene = load_scene(a.scene, options);
  double load_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  SceneStats s = compute_stats(scene);
  OneTexelStats one_texel = collapse_one_texel_textures(scene, /*apply=*/false);
  Json j = {
      {"scene", a.scene},
      {"triangles", s.triangles},
      {"vertices", s.vertices},
      {"meshes", s.meshes},
      {"materials", s.materials},
      {"textures", s.textures},
      {"emissive_triangles", s.emissive_triangles},
      {"point_lights", s.point_lights},
      {"environment",
       s.environment ? (scene.environment.map.empty() ? "constant" : "map") : "none"},
      {"lights", s.lights},
      {"surface_area", s.surface_area},
      {"emissive_area", s.emissive_area},
      {"bounds_min", vec_json(s.bounds.lo)},
      {"bounds_max", vec_json(s.bounds.hi)},
      {"cameras", scene.cameras.size()},
      {"camera_paths", scene.camera_paths.size()},
      {"load_ms", load_ms},
      {"memory_bytes", s.memory_bytes},
      // Textured triangles whose UVs fall in one texel (render folds them into constant colours).
      {"one_texel_triangles", one_texel.candidates},
      {"one_texel_foldable", one_texel.collapsed},
      {"notes", scene.notes},
  };
  SceneIndicators scene_indicators = compute_scene_indicators(scene);
  Json indicators = Json::array();
  for (const CameraDesc& camera : scene.cameras) {
    Indicators ind = compute_indicators(scene_indicators, camera);
    Json values = Json::object();
    for (size_t i = 0; i < kIndicatorCount; ++i) values[indicator_infos()[i].name] = ind[i];
    indicators.push_back({{"camera", camera.name}, {"values", values}});
  }
  j["indicators"] = indicators;

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
    Indicators ind = compute_indicators(scene_indicators, scene.cameras[0]);
    for (size_t i = 0; i < kIndicatorCount; ++i)
      std::cout << "  " << indicator_infos()[i].name
                << std::string(26 - std::string(indicator_infos()[i].name).size(), ' ') << ind[i]
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
