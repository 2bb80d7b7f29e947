#include "bench/scene_report.h"

#include "scene/indicators.h"
#include "scene/one_texel.h"
#include "scene/stats.h"

namespace tuneray {

namespace {

using Json = nlohmann::ordered_json;

Json vec_json(Vec3f v) {
  return {v.x, v.y, v.z};
}

}  // namespace

Json scene_report_json(Scene& scene, const std::string& spec, double load_ms) {
  SceneStats s = compute_stats(scene);
  OneTexelStats one_texel = collapse_one_texel_textures(scene, /*apply=*/false);
  Json j = {
      {"scene", spec},
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
  return j;
}

}  // namespace tuneray
