// The 17 numbers that describe a scene and a view to the autotuner (DESIGN §4). Each comes
// with a fixed range for normalisation; quantities spanning orders of magnitude are given as
// log10 so that a fixed linear range covers every real scene.
#pragma once

#include <array>
#include <string>

#include "scene/camera.h"
#include "scene/scene.h"

namespace tuneray {

inline constexpr size_t kIndicatorCount = 17;

struct IndicatorInfo {
  const char* name;
  double lo, hi;  // range of the value as stored (after any log10)
  const char* meaning;
};

// Names, ranges and meanings, in the order of Indicators::values.
const std::array<IndicatorInfo, kIndicatorCount>& indicator_infos();

struct Indicators {
  std::array<double, kIndicatorCount> values{};
  double operator[](size_t i) const { return values[i]; }
};

// Scene-only part (everything but the camera), computed once per scene: O(triangles).
struct SceneIndicators {
  double meshes = 0, triangles = 0, lights = 0;
  double diffuse_ratio = 0;
  double diagonal = 0;
  double area_ratio = 0, light_area_ratio = 0, area_per_mesh_ratio = 0;
  double mesh_area_variance_mean = 0, mesh_area_variance_variance = 0;
  BBox bounds;
};

SceneIndicators compute_scene_indicators(const Scene& scene);
// Adds the camera (position and target in the scene's unit box, field of view).
Indicators compute_indicators(const SceneIndicators& scene, const CameraDesc& camera);
inline Indicators compute_indicators(const Scene& scene, const CameraDesc& camera) {
  return compute_indicators(compute_scene_indicators(scene), camera);
}

}  // namespace tuneray
