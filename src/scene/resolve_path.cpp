#include "scene/resolve_path.h"

#include <cstdlib>
#include <filesystem>
#include <vector>

#include "scene/load.h"

namespace tuneray {

std::string resolve_scene_path(const std::string& name, const std::string& referrer,
                               const std::string& scenes_dir) {
  namespace fs = std::filesystem;
  fs::path p(name);
  if (p.is_absolute()) {
    if (fs::exists(p)) return name;
    throw SceneError(referrer + ": file '" + name + "' not found");
  }
  std::vector<fs::path> bases = {fs::path(referrer).parent_path()};
  if (!scenes_dir.empty()) bases.emplace_back(scenes_dir);
  if (const char* env = std::getenv("TUNERAY_SCENES"); env && *env) bases.emplace_back(env);
  std::string tried;
  for (const fs::path& base : bases) {
    fs::path candidate = base / p;
    if (fs::exists(candidate)) return candidate.string();
    tried += (tried.empty() ? "" : ", ") + candidate.string();
  }
  throw SceneError(referrer + ": file '" + name + "' not found (tried " + tried + ")");
}

}  // namespace tuneray
