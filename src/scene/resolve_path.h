// Where a file named in a JSON scene is looked for.
#pragma once

#include <string>

namespace tuneray {

// `name` if absolute; otherwise the first existing file among: next to `referrer` (the JSON
// file), under `scenes_dir`, under $TUNERAY_SCENES. Throws SceneError listing the places tried.
std::string resolve_scene_path(const std::string& name, const std::string& referrer,
                               const std::string& scenes_dir);

}  // namespace tuneray
