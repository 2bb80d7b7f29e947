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

}  // namespace tuneray
