#include "scene/load.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "scene/builtins.h"
#include "scene/finalize.h"
#include "scene/loaders.h"

namespace tuneray {

namespace {

struct Builtin {
  const char* name;
  Scene (*make)();
};

constexpr Builtin kBuiltins[] = {
    {"cornell", make_cornell_scene},
    {"voxels", make_voxels_scene},
    {"mixed", make_mixed_scene},
    {"furnace", make_furnace_scene},
    {"furnace_ggx", make_furnace_ggx_scene},
    {"sky", make_sky_scene},
};

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> names;
  for (const Builtin& b : kBuiltins) names.emplace_back(b.name);
  return names;
}

bool is_builtin_scene(const std::string& name) {
  return std::any_of(std::begin(kBuiltins), std::end(kBuiltins),
                     [&](const Builtin& b) { return name == b.name; });
}

Scene make_builtin_scene(const std::string& name) {
  for (const Builtin& b : kBuiltins)
    if (name == b.name) return b.make();
  throw SceneError(name + ": unknown built-in scene");
}

std::string mesh_format(const std::string& path) {
  std::string ext = lower_extension(path);
  if (ext == ".obj" || ext == ".ply" || ext == ".gltf" || ext == ".glb") return ext.substr(1);
  return "";
}

Scene load_mesh_file(const std::string& path) {
  std::string format = mesh_format(path);
  if (format == "obj") return load_obj(path);
  if (!format.empty()) return load_with_assimp(path);
  throw SceneError(path + ": unknown scene file extension '" + lower_extension(path) +
                   "' (expected .obj, .ply, .gltf, .glb, .json or .ecs, or a built-in name)");
}

Scene load_scene(const std::string& spec, const LoadOptions& options) {
  Scene scene;
  if (is_builtin_scene(spec))
    scene = make_builtin_scene(spec);
  else if (const std::string ext = lower_extension(spec); ext == ".json")
    scene = load_json_scene(spec, options);
  else if (ext == ".ecs")
    scene = load_ecs_scene(spec);
  else
    scene = load_mesh_file(spec);
  finalize_scene(scene);
  return scene;
}

}  // namespace tuneray
