#include "bench/scene_paths.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

namespace tuneray {

namespace fs = std::filesystem;

namespace {
// The checkout holding the running executable (build/src/app/tuneray → three levels up).
fs::path checkout_root() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  return exe.parent_path().parent_path().parent_path().parent_path();
}
}  // namespace

std::string find_shared_scenes_dir(const std::string& override_dir) {
  if (!override_dir.empty()) return override_dir;
  if (const char* env = std::getenv("TUNERAY_SCENES")) return env;
  std::vector<fs::path> candidates = {"../shared/scenes", "shared/scenes", "../../shared/scenes"};
  if (fs::path root = checkout_root(); !root.empty())
    candidates.push_back(root.parent_path() / "shared" / "scenes");
  std::error_code ec;
  for (const auto& c : candidates)
    if (fs::is_directory(c, ec)) return fs::weakly_canonical(c).string();
  return "";
}

std::vector<std::string> shared_scene_files(const std::string& scenes_dir) {
  // Ordered by triangle count (see ../shared/scenes/README.md).
  static const char* kFiles[] = {
      "cornell-box/CornellBox-Original.obj",
      "cornell-box/CornellBox-Water.obj",
      "teapot/teapot.obj",
      "stanford-bunny/bunny.obj",
      "lost-empire/lost_empire.obj",
      "sports-car/sportsCar.obj",
      "conference/conference.obj",
      "bmw-m6/bmw-m6.obj",
  };
  std::vector<std::string> out;
  if (scenes_dir.empty()) return out;
  for (const char* f : kFiles) {
    fs::path p = fs::path(scenes_dir) / f;
    if (fs::exists(p)) out.push_back(p.string());
  }
  return out;
}

}  // namespace tuneray

namespace tuneray {

namespace {
// scenes/ relative to the working directory, else the executable's checkout; empty if neither.
fs::path checkout_scenes_dir() {
  std::error_code ec;
  for (const fs::path& dir : {fs::path("scenes"), checkout_root() / "scenes"})
    if (fs::is_directory(dir, ec)) return dir;
  return {};
}
}  // namespace

std::vector<std::string> all_scene_json_files() {
  std::vector<std::string> out;
  fs::path dir = checkout_scenes_dir();
  if (dir.empty()) return out;
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".json") out.push_back((dir / e.path().filename()).string());
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> shared_scene_json_files() {
  static const char* kFiles[] = {
      "cornell-box-water.json", "teapot.json",     "stanford-bunny.json", "lost-empire.json",
      "sports-car.json",        "conference.json", "bmw-m6.json"};
  std::vector<std::string> out;
  for (const fs::path& dir : {fs::path("scenes"), checkout_root() / "scenes"}) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    for (const char* f : kFiles)
      if (fs::exists(dir / f)) out.push_back((dir / f).string());
    if (!out.empty()) break;
  }
  return out;
}

}  // namespace tuneray
