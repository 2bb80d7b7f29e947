// What `tuneray info` reports on a scene: its statistics, load time, memory, one-texel
// candidates, and the tuner's indicators for each of its cameras.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "scene/scene.h"

namespace tuneray {

// `spec` as given to load_scene. "indicators" holds one {"camera", "values"} object per camera.
// The scene is not changed (the one-texel count is a dry run, which takes it mutable).
nlohmann::ordered_json scene_report_json(Scene& scene, const std::string& spec, double load_ms);

}  // namespace tuneray
