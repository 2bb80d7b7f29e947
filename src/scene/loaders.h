// The individual loaders behind load_scene(); each returns a scene without cameras or default
// lighting (finalize_scene adds those) and throws SceneError naming the file on bad input.
#pragma once

#include <string>

#include "scene/load.h"

namespace tuneray {

Scene load_obj(const std::string& path);
// PLY, glTF (.gltf/.glb) and the other formats assimp reads.
Scene load_with_assimp(const std::string& path);
// A mesh file by its (case-insensitive) extension: .obj, .ply, .gltf, .glb; "" for others.
std::string mesh_format(const std::string& path);
Scene load_mesh_file(const std::string& path);
// Embree's tutorial scene files (.ecs): -i meshes (.obj, .ply, .gltf, .glb; paths relative to the
// file), -pointlight, -ambientlight and the -vp/-vi/-vd/-vu/-fov camera. The meshes' own emission
// is dropped, as Embree's pathtracer lights such a scene only by the file's lights.
Scene load_ecs_scene(const std::string& path);
Scene load_json_scene(const std::string& path, const LoadOptions& options);
// Throws SceneError for an unknown name.
Scene make_builtin_scene(const std::string& name);
bool is_builtin_scene(const std::string& name);

}  // namespace tuneray
