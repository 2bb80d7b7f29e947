// JSON scene files (format in docs/scenes.md): meshes plus cameras, camera paths, lights,
// environment and material overrides.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "image/io.h"
#include "image/texel_check.h"
#include "scene/json_fields.h"
#include "scene/loaders.h"
#include "scene/merge.h"
#include "scene/resolve_path.h"

namespace tuneray {

namespace {

CameraDesc parse_camera(const JsonFields& j, const std::string& default_name) {
  j.expect_object({"name", "position", "target", "up", "fov", "lens_radius", "focus_distance"});
  CameraDesc c;
  c.name = j.string_or("name", default_name);
  c.position = j.child("position").vec3();
  c.target = j.child("target").vec3();
  c.up = j.vec3_or("up", c.up);
  c.vfov_deg = j.number_or("fov", c.vfov_deg);
  c.lens_radius = j.number_or("lens_radius", c.lens_radius);
  c.focus_distance = j.number_or("focus_distance", c.focus_distance);
  if (!(length(c.target - c.position) > 0)) j.fail("position and target coincide");
  if (!(length(cross(c.target - c.position, c.up)) > 0)) j.fail("up is parallel to the view");
  if (!(c.vfov_deg > 0 && c.vfov_deg < 180)) j.child("fov").fail("must be in (0, 180) degrees");
  if (c.lens_radius < 0) j.child("lens_radius").fail("must not be negative");
  if (c.focus_distance < 0) j.child("focus_distance").fail("must not be negative");
  return c;
}

CameraPath parse_camera_path(const JsonFields& j, size_t index) {
  j.expect_object({"name", "keyframes"});
  CameraPath path;
  path.name = j.string_or("name", "path_" + std::to_string(index));
  JsonFields keys = j.child("keyframes");
  if (keys.array_size() == 0) keys.fail("needs at least one keyframe");
  for (size_t i = 0; i < keys.array_size(); ++i)
    path.keyframes.push_back(parse_camera(keys.element(i), path.name + "_" + std::to_string(i)));
  return path;
}

void apply_material_override(const JsonFields& j, Material& m) {
  j.expect_object({"type", "base_color", "specular_color", "transmittance", "emission", "roughness",
                   "roughness_u", "roughness_v", "ior", "two_sided_emission"});
  if (j.has("type")) {
    JsonFields t = j.child("type");
    auto type = material_type_from_string(t.string());
    if (!type) t.fail("unknown material type (lambert, mirror, dielectric, glossy, principled)");
    m.type = *type;
  }
  if (j.has("base_color")) m.base_color = j.child("base_color").color();
  if (j.has("specular_color")) m.specular_color = j.child("specular_color").color();
  if (j.has("transmittance")) m.transmittance = j.child("transmittance").color();
  if (j.has("emission")) m.emission = j.child("emission").color();
  auto roughness = [&](const char* key, float& out) {
    if (!j.has(key)) return;
    JsonFields r = j.child(key);
    out = r.number();
    if (!(out > 0 && out <= 1)) r.fail("must be in (0, 1]");
  };
  roughness("roughness", m.roughness_u);
  roughness("roughness", m.roughness_v);
  roughness("roughness_u", m.roughness_u);
  roughness("roughness_v", m.roughness_v);
  if (j.has("ior")) {
    JsonFields ior = j.child("ior");
    m.ior = ior.number();
    if (!(m.ior > 0)) ior.fail("must be positive");
  }
  if (j.has("two_sided_emission")) m.two_sided_emission = j.child("two_sided_emission").boolean();
}

// Keys are material names from the meshes; a name that matches nothing is an error (a typo).
void apply_material_overrides(const JsonFields& j, Scene& scene) {
  if (!j.value().is_object()) j.fail("expected an object of material names");
  for (const auto& item : j.value().items()) {
    JsonFields entry = j.child(item.key().c_str());
    bool found = false;
    for (Material& m : scene.materials)
      if (m.name == item.key()) {
        apply_material_override(entry, m);
        found = true;
      }
    if (!found) entry.fail("no material of this name in the meshes");
  }
}

void parse_environment(const JsonFields& j, const std::string& file, const LoadOptions& options,
                       Environment& env) {
  j.expect_object({"color", "map", "scale"});
  if (j.has("color") == j.has("map")) j.fail("needs exactly one of 'color' and 'map'");
  env.scale = j.number_or("scale", 1.0f);
  if (env.scale < 0) j.child("scale").fail("must not be negative");
  if (j.has("color")) {
    env.constant = j.child("color").color();
    return;
  }
  std::string path = resolve_scene_path(j.child("map").string(), file, options.scenes_dir);
  try {
    env.map = read_image(path);
  } catch (const std::exception& e) {
    throw SceneError(file + ": environment map '" + path + "': " + e.what());
  }
  if (auto bad = find_bad_texel(env.map))
    throw SceneError(file + ": environment map '" + path + "': " + describe_bad_texel(*bad));
}

Scene load_meshes(const JsonFields& root, const std::string& file, const LoadOptions& options) {
  if (root.has("mesh") == root.has("meshes")) root.fail("needs exactly one of 'mesh' and 'meshes'");
  std::vector<JsonFields> names;
  if (root.has("mesh")) {
    names.push_back(root.child("mesh"));
  } else {
    JsonFields list = root.child("meshes");
    if (list.array_size() == 0) list.fail("needs at least one mesh");
    for (size_t i = 0; i < list.array_size(); ++i) names.push_back(list.element(i));
  }
  Scene scene;
  for (const JsonFields& name : names) {
    std::string path = resolve_scene_path(name.string(), file, options.scenes_dir);
    if (mesh_format(path).empty()) name.fail("not a mesh file (.obj, .ply, .gltf, .glb)");
    append_geometry(scene, load_mesh_file(path));
  }
  return scene;
}

}  // namespace

Scene load_json_scene(const std::string& file, const LoadOptions& options) {
  std::ifstream in(file);
  if (!in) throw SceneError(file + ": cannot open file");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw SceneError(file + ": invalid JSON: " + e.what());
  }
  JsonFields root(doc, file, "");
  root.expect_object({"name", "mesh", "meshes", "cameras", "camera_paths", "environment",
                      "light_scale", "point_lights", "materials"});

  Scene scene = load_meshes(root, file, options);
  scene.source = file;
  scene.name = root.string_or("name", std::filesystem::path(file).stem().string());

  if (root.has("materials")) apply_material_overrides(root.child("materials"), scene);
  if (root.has("cameras")) {
    JsonFields cams = root.child("cameras");
    for (size_t i = 0; i < cams.array_size(); ++i)
      scene.cameras.push_back(parse_camera(cams.element(i), "camera_" + std::to_string(i)));
  }
  if (root.has("camera_paths")) {
    JsonFields paths = root.child("camera_paths");
    for (size_t i = 0; i < paths.array_size(); ++i)
      scene.camera_paths.push_back(parse_camera_path(paths.element(i), i));
  }
  if (root.has("environment"))
    parse_environment(root.child("environment"), file, options, scene.environment);
  if (root.has("light_scale")) {
    JsonFields s = root.child("light_scale");
    scene.light_scale = s.number();
    if (scene.light_scale < 0) s.fail("must not be negative");
  }
  if (root.has("point_lights")) {
    JsonFields lights = root.child("point_lights");
    for (size_t i = 0; i < lights.array_size(); ++i) {
      JsonFields l = lights.element(i);
      l.expect_object({"position", "intensity"});
      scene.point_lights.push_back({l.child("position").vec3(), l.child("intensity").color()});
    }
  }
  return scene;
}

}  // namespace tuneray
