#include <gtest/gtest.h>

#include <cstdlib>

#include "image/io.h"
#include "scene/load.h"
#include "scene_files.h"

namespace tuneray {
namespace {

using ::testing::HasSubstr;
using testing::load_error;
using testing::SceneFiles;

// Two materials on two triangles, no lights.
void write_mesh(const SceneFiles& files, const std::string& name = "mesh.obj") {
  files.write("mesh.mtl",
              "newmtl paint\nKd 0.5 0.5 0.5\nillum 1\nnewmtl chrome\nKs 1 1 1\nillum 5\n");
  files.write(name,
              "mtllib mesh.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
              "usemtl paint\nf 1 2 3\nusemtl chrome\nf 2 4 3\n");
}

TEST(JsonScene, FullExample) {
  SceneFiles files;
  write_mesh(files);
  std::string json = files.write("s.json", R"({
    "name": "demo",
    "mesh": "mesh.obj",
    "cameras": [{"name": "main", "position": [0, 0, 5], "target": [0.5, 0.5, 0],
                 "up": [0, 1, 0], "fov": 30, "lens_radius": 0.01, "focus_distance": 5}],
    "camera_paths": [{"name": "p", "keyframes": [
        {"position": [0, 0, 5], "target": [0, 0, 0]},
        {"position": [5, 0, 5], "target": [0, 0, 0], "fov": 60}]}],
    "environment": {"color": [0.1, 0.2, 0.3], "scale": 2},
    "light_scale": 3,
    "point_lights": [{"position": [1, 2, 3], "intensity": [10, 10, 10]}],
    "materials": {
      "paint": {"type": "glossy", "specular_color": [0.9, 0.8, 0.7], "roughness_u": 0.3,
                "roughness_v": 0.1},
      "chrome": {"type": "dielectric", "ior": 1.7, "emission": 2, "roughness": 0.2}
    }
  })");
  Scene s = load_scene(json);
  EXPECT_EQ(s.name, "demo");
  EXPECT_EQ(s.triangles.size(), 2u);
  ASSERT_EQ(s.cameras.size(), 1u);
  const CameraDesc& c = s.cameras[0];
  EXPECT_EQ(c.name, "main");
  EXPECT_EQ(c.target, Vec3f(0.5f, 0.5f, 0));
  EXPECT_FLOAT_EQ(c.vfov_deg, 30.0f);
  EXPECT_FLOAT_EQ(c.lens_radius, 0.01f);
  EXPECT_FLOAT_EQ(c.focus_distance, 5.0f);
  ASSERT_EQ(s.camera_paths.size(), 1u);
  ASSERT_EQ(s.camera_paths[0].keyframes.size(), 2u);
  EXPECT_FLOAT_EQ(s.camera_paths[0].keyframes[0].vfov_deg, 45.0f);  // default
  EXPECT_FLOAT_EQ(s.camera_paths[0].keyframes[1].vfov_deg, 60.0f);
  EXPECT_EQ(s.environment.constant, Color(0.1f, 0.2f, 0.3f));
  EXPECT_FLOAT_EQ(s.environment.scale, 2.0f);
  EXPECT_FLOAT_EQ(s.light_scale, 3.0f);
  ASSERT_EQ(s.point_lights.size(), 1u);
  EXPECT_EQ(s.point_lights[0].position, Vec3f(1, 2, 3));
  const Material& paint = s.materials[0];
  EXPECT_EQ(paint.type, MaterialType::kGlossy);
  EXPECT_EQ(paint.base_color, Color(0.5f));  // untouched by the override
  EXPECT_EQ(paint.specular_color, Color(0.9f, 0.8f, 0.7f));
  EXPECT_FLOAT_EQ(paint.roughness_u, 0.3f);
  EXPECT_FLOAT_EQ(paint.roughness_v, 0.1f);
  const Material& chrome = s.materials[1];
  EXPECT_EQ(chrome.type, MaterialType::kDielectric);
  EXPECT_FLOAT_EQ(chrome.ior, 1.7f);
  EXPECT_EQ(chrome.emission, Color(2.0f));
  EXPECT_FLOAT_EQ(chrome.roughness_u, 0.2f);
  EXPECT_TRUE(s.notes.empty());
}

TEST(JsonScene, SeveralMeshesAreMerged) {
  SceneFiles files;
  write_mesh(files, "a.obj");
  files.write("b.obj", "v 0 0 1\nv 1 0 1\nv 0 1 1\nf 1 2 3\n");
  Scene s = load_scene(files.write("s.json", R"({"meshes": ["a.obj", "b.obj"]})"));
  ASSERT_EQ(s.triangles.size(), 3u);
  ASSERT_EQ(s.materials.size(), 3u);  // paint, chrome, default
  EXPECT_EQ(s.material_ids[2], 2u);
  EXPECT_EQ(s.triangles[2].v[0], 4u);  // after a.obj's four vertices
  EXPECT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[1].first, 2u);
}

TEST(JsonScene, MeshPathsResolveThroughScenesDirAndEnvironment) {
  SceneFiles files;
  write_mesh(files, "lib/mesh.obj");
  files.write("lib/mesh.mtl", "newmtl paint\nnewmtl chrome\n");
  std::string json = files.write("elsewhere/s.json", R"({"mesh": "mesh.obj"})");
  EXPECT_THAT(load_error(json), HasSubstr("'mesh.obj' not found"));
  LoadOptions options;
  options.scenes_dir = files.path("lib");
  EXPECT_EQ(load_error(json, options), "");
  setenv("TUNERAY_SCENES", files.path("lib").c_str(), 1);
  EXPECT_EQ(load_error(json), "");
  unsetenv("TUNERAY_SCENES");
}

TEST(JsonScene, EnvironmentMap) {
  SceneFiles files;
  write_mesh(files);
  write_image(files.path("sky.pfm"), Image(4, 2, Color(0.25f, 0.5f, 2.0f)));
  Scene s = load_scene(files.write(
      "s.json", R"({"mesh": "mesh.obj", "environment": {"map": "sky.pfm", "scale": 0.5}})"));
  ASSERT_EQ(s.environment.map.width(), 4);
  EXPECT_EQ(s.environment.map.at(3, 1), Color(0.25f, 0.5f, 2.0f));
  EXPECT_FLOAT_EQ(s.environment.scale, 0.5f);
}

struct BadJson {
  const char* text;
  const char* expected;  // besides the file name
};

class JsonErrors : public ::testing::TestWithParam<BadJson> {};

TEST_P(JsonErrors, NameTheFileAndTheProblem) {
  SceneFiles files;
  write_mesh(files);
  std::string json = files.write("bad.json", GetParam().text);
  std::string e = load_error(json);
  EXPECT_THAT(e, HasSubstr("bad.json"));
  EXPECT_THAT(e, HasSubstr(GetParam().expected));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, JsonErrors,
    ::testing::Values(
        BadJson{R"({"mesh": "mesh.obj",)", "invalid JSON"},
        BadJson{R"([1, 2])", "top level: expected an object"},
        BadJson{R"({"mesh": "mesh.obj", "camera": []})", "camera: unknown key"},
        BadJson{R"({"meshes": ["mesh.obj"], "mesh": "mesh.obj"})", "exactly one of"},
        BadJson{R"({"mesh": 3})", "mesh: expected a string"},
        BadJson{R"({"mesh": "mesh.obj", "cameras": [{"position": [0, 0, 1], "target": [0, 0, 0],
                    "fov": "wide"}]})",
                "cameras[0].fov: expected a number"},
        BadJson{R"({"mesh": "mesh.obj", "cameras": [{"position": [0, 0], "target": [0, 0, 0]}]})",
                "cameras[0].position: expected an array of 3 numbers"},
        BadJson{R"({"mesh": "mesh.obj", "cameras": [{"position": [0, 0, 1]}]})",
                "cameras[0]: missing key 'target'"},
        BadJson{
            R"({"mesh": "mesh.obj", "cameras": [{"position": [1, 1, 1], "target": [1, 1, 1]}]})",
            "coincide"},
        BadJson{R"({"mesh": "mesh.obj", "camera_paths": [{"keyframes": [{"position": [0, 0, 1],
                    "target": [0, 0, 0], "lens": 1}]}]})",
                "camera_paths[0].keyframes[0].lens: unknown key"},
        BadJson{R"({"mesh": "mesh.obj", "materials": {"paint": {"roughnes": 0.5}}})",
                "materials.paint.roughnes: unknown key"},
        BadJson{R"({"mesh": "mesh.obj", "materials": {"paint": {"type": "velvet"}}})",
                "unknown material type"},
        BadJson{R"({"mesh": "mesh.obj", "materials": {"pain": {"type": "mirror"}}})",
                "materials.pain: no material of this name"},
        BadJson{R"({"mesh": "mesh.obj", "materials": {"paint": {"roughness": 0}}})",
                "must be in (0, 1]"},
        BadJson{R"({"mesh": "mesh.obj", "environment": {"color": [1, 1, 1], "map": "x.hdr"}})",
                "exactly one of 'color' and 'map'"},
        BadJson{R"({"mesh": "mesh.obj", "environment": {"map": "missing.hdr"}})",
                "'missing.hdr' not found"},
        BadJson{R"({"mesh": "mesh.obj", "point_lights": [{"position": [0, 1, 0],
                    "intensity": [-1, 0, 0]}]})",
                "point_lights[0].intensity: colour components must not be negative"},
        BadJson{R"({"mesh": "mesh.obj", "light_scale": -1})", "light_scale: must not be negative"},
        BadJson{R"({"mesh": "bad.json"})", "not a mesh file"}));

}  // namespace
}  // namespace tuneray
