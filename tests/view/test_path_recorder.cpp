#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "common/temp_dir.h"
#include "scene/builtins.h"
#include "scene/load.h"
#include "view/path_recorder.h"

namespace tuneray {
namespace {

TEST(PathRecorder, SkipsRepeatedCameras) {
  PathRecorder recorder("flight");
  CameraDesc a = look_at("a", Vec3f(0, 0, 5), Vec3f(0), 45);
  CameraDesc b = look_at("b", Vec3f(1, 0, 5), Vec3f(0), 45);
  recorder.add(a);
  recorder.add(a);
  recorder.add(b);
  recorder.add(b);
  recorder.add(a);
  EXPECT_EQ(recorder.path().keyframes.size(), 3u);
}

TEST(PathRecorder, EmptyPathIsAnError) {
  EXPECT_THROW(PathRecorder("none").to_json(), std::runtime_error);
}

// The recorded file is what a scene's "camera_paths" holds: a scene that includes it loads
// the same keyframes back.
TEST(PathRecorder, SceneFilesReadTheRecordedPath) {
  testing::TempDir dir;
  PathRecorder recorder("flight");
  CameraDesc a = look_at("a", Vec3f(0.1f, 0.2f, 5), Vec3f(0, 0.3f, 0), 45);
  CameraDesc b = look_at("b", Vec3f(1.7f, -0.4f, 4.1f), Vec3f(0.2f, 0, 0), 61.5f);
  b.lens_radius = 0.05f;
  b.focus_distance = 3.5f;
  recorder.add(a);
  recorder.add(b);
  recorder.write(dir.file("flight.json"));

  dir.write_bytes("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  nlohmann::json path = nlohmann::json::parse(std::ifstream(dir.file("flight.json")));
  nlohmann::json scene = {{"mesh", "tri.obj"},
                          {"point_lights", {{{"position", {0, 0, 3}}, {"intensity", 1}}}},
                          {"camera_paths", {path}}};
  dir.write_bytes("scene.json", scene.dump());
  Scene loaded = load_scene(dir.file("scene.json"));
  ASSERT_EQ(loaded.camera_paths.size(), 1u);
  const CameraPath& p = loaded.camera_paths[0];
  EXPECT_EQ(p.name, "flight");
  ASSERT_EQ(p.keyframes.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const CameraDesc& want = recorder.path().keyframes[i];
    EXPECT_EQ(p.keyframes[i].position, want.position);
    EXPECT_EQ(p.keyframes[i].target, want.target);
    EXPECT_EQ(p.keyframes[i].vfov_deg, want.vfov_deg);
    EXPECT_EQ(p.keyframes[i].lens_radius, want.lens_radius);
    EXPECT_EQ(p.keyframes[i].focus_distance, want.focus_distance);
  }
}

}  // namespace
}  // namespace tuneray
