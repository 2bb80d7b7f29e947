// Where the shared real scenes live, and the list of them that benchmarks default to.
#pragma once

#include <string>
#include <vector>

namespace tuneray {

// The folder holding the shared scenes: $TUNERAY_SCENES, else ../shared/scenes or
// ./shared/scenes relative to the working directory or the executable's checkout. Empty if none.
std::string find_shared_scenes_dir(const std::string& override_dir = "");

// Paths of the mesh files of the shared scenes, smallest first (empty when none is found).
std::vector<std::string> shared_scene_files(const std::string& scenes_dir);

// The JSON scene files of this checkout (scenes/*.json: cameras, camera paths and lights for
// every shared scene), smallest scene first. Their meshes resolve against the shared scenes
// folder. Empty when the checkout's scenes/ folder is not found.
std::vector<std::string> shared_scene_json_files();

// Every scenes/*.json of this checkout, by name (the quality benchmark's default: every shared
// scene, both Cornell boxes included). Empty when the folder is not found.
std::vector<std::string> all_scene_json_files();

}  // namespace tuneray
