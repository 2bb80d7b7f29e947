// Entry point for getting a Scene: a built-in name, a mesh file (OBJ/PLY/glTF) or a JSON scene.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace tuneray {

// Every loading problem (missing file, malformed data, out-of-range index, NaN vertex, unknown
// extension, bad JSON) throws SceneError whose message names the file and the problem.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LoadOptions {
  // Where relative mesh paths in JSON scenes are resolved besides the JSON file's own folder
  // (the CLI's --scenes-dir / $TUNERAY_SCENES).
  std::string scenes_dir;
};

// `spec`: "cornell", "voxels", "mixed", ... (see builtin_scene_names()), or a path to
// .obj/.ply/.gltf/.glb/.json. The result has normals for every vertex, at least one camera, and
// material ids in range.
Scene load_scene(const std::string& spec, const LoadOptions& options = {});

std::vector<std::string> builtin_scene_names();

}  // namespace tuneray
