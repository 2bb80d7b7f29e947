// Embree's tutorial scene files (.ecs): the command-line options its tutorials read from a file.
// What they say about the scene (its meshes, lights and camera) is read; what they say about a
// tutorial's display is refused by name, so a scene never silently renders differently from how
// Embree's pathtracer shows it.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "scene/loaders.h"
#include "scene/merge.h"

namespace tuneray {

namespace {

class EcsTokens {
 public:
  EcsTokens(const std::string& path, std::istream& in) : path_(path) {
    std::string line;
    while (std::getline(in, line)) {
      line = line.substr(0, line.find('#'));  // a comment runs to the end of its line
      std::istringstream words(line);
      for (std::string w; words >> w;) tokens_.push_back(w);
    }
  }
  bool done() const { return next_ == tokens_.size(); }
  std::string word(const std::string& option) {
    if (done()) throw SceneError(path_ + ": " + option + " needs a value, the file ends first");
    return tokens_[next_++];
  }
  float number(const std::string& option) {
    const std::string w = word(option);
    size_t used = 0;
    float v = 0.0f;
    try {
      v = std::stof(w, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != w.size() || !std::isfinite(v))
      throw SceneError(path_ + ": " + option + " expects finite numbers, got '" + w + "'");
    return v;
  }
  Vec3f vec3(const std::string& option) {
    const float x = number(option), y = number(option);
    return {x, y, number(option)};
  }
  Color light(const std::string& option) {
    const Vec3f rgb = vec3(option);
    if (rgb.x < 0 || rgb.y < 0 || rgb.z < 0)
      throw SceneError(path_ + ": " + option + " has a negative colour");
    return Color(rgb.x, rgb.y, rgb.z);
  }

 private:
  std::string path_;
  std::vector<std::string> tokens_;
  size_t next_ = 0;
};

}  // namespace

Scene load_ecs_scene(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SceneError(path + ": cannot open the file");
  EcsTokens tokens(path, in);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();

  // Meshes bring no lights, sky or cameras of their own (append_geometry): the file's are the
  // scene's.
  Scene scene;
  CameraDesc camera;
  std::optional<Vec3f> direction;  // -vd: the view direction instead of a point looked at
  bool camera_given = false;       // -vp, -vi or -vd (else the automatic camera)
  while (!tokens.done()) {
    std::string option = tokens.word("");
    // Embree's tutorials take both -name and --name.
    const std::string name = option.rfind("--", 0) == 0  ? option.substr(2)
                             : option.rfind('-', 0) == 0 ? option.substr(1)
                                                         : "";
    if (name == "i") {
      const std::filesystem::path mesh = folder / tokens.word(option);
      if (mesh_format(mesh.string()).empty())
        throw SceneError(path + ": -i " + mesh.string() +
                         ": only .obj, .ply, .gltf and .glb meshes are read (not Embree's XML "
                         "scenes)");
      append_geometry(scene, load_mesh_file(mesh.string()));
    } else if (name == "pointlight") {
      const Vec3f position = tokens.vec3(option);
      scene.point_lights.push_back({position, tokens.light(option)});
    } else if (name == "ambientlight") {
      scene.environment.constant = scene.environment.constant + tokens.light(option);
    } else if (name == "vp") {
      camera.position = tokens.vec3(option);
      camera_given = true;
    } else if (name == "vi") {
      camera.target = tokens.vec3(option);
      direction.reset();
      camera_given = true;
    } else if (name == "vd") {
      direction = tokens.vec3(option);  // the target follows once the position is known
      camera_given = true;
    } else if (name == "vu") {
      camera.up = tokens.vec3(option);
    } else if (name == "fov") {
      camera.vfov_deg = tokens.number(option);
      if (!(camera.vfov_deg > 0.0f && camera.vfov_deg < 180.0f))
        throw SceneError(path + ": " + option + " must lie in (0, 180) degrees");
    } else {
      throw SceneError(path + ": option '" + option +
                       "' is not supported (read: -i, -pointlight, -ambientlight, -vp, -vi, -vd, "
                       "-vu, -fov; Embree's -dirlight, --righthanded and display options are not)");
    }
  }
  if (scene.triangles.empty()) throw SceneError(path + ": no -i mesh with triangles");
  if (direction) camera.target = camera.position + *direction;
  if (camera_given) {
    if (length(camera.target - camera.position) == 0.0f)
      throw SceneError(path + ": the camera looks at its own position (-vp equals -vi)");
    if (length(cross(camera.target - camera.position, camera.up)) == 0.0f)
      throw SceneError(path + ": -vu is parallel to the view direction");
    scene.cameras = {camera};
  }
  // Embree's pathtracer lights a scene only by these lights: its OBJ materials do not emit.
  for (Material& m : scene.materials) m.emission = Color(0.0f);
  scene.name = std::filesystem::path(path).stem().string();
  scene.source = path;
  return scene;
}

}  // namespace tuneray
