#include <gtest/gtest.h>

#include "scene/load.h"
#include "scene_files.h"

namespace tuneray {
namespace {

using ::testing::HasSubstr;
using testing::load_error;
using testing::SceneFiles;

// A lit quad: the mesh's own emission must not survive into an .ecs scene.
const char* kMtl = "newmtl lamp\nKd 0.5 0.5 0.5\nKe 10 10 10\n";
const char* kQuad =
    "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl lamp\nf 1 2 3\nf 1 3 4\n";

TEST(EcsScene, ReadsMeshLightsAndCameraAsEmbreesTutorialsDo) {
  SceneFiles files;
  files.write("quad.mtl", kMtl);
  files.write("meshes/quad.obj", std::string(kQuad).replace(7, 8, "../quad.mtl"));
  const std::string ecs = files.write(
      "box.ecs",
      "# a comment\n-i meshes/quad.obj\n-pointlight 1 2 3 10 20 30\n--pointlight 0 0 5 1 1 1\n"
      "-ambientlight 0.25 0.5 0.75\n--vp 0 0 -4 --vi 0.5 0.5 0 --vu 0 1 0 -fov 37\n");
  ASSERT_EQ(load_scene(files.path("meshes/quad.obj")).emissive_triangle_count(), 2u);
  const Scene s = load_scene(ecs);
  EXPECT_EQ(s.triangle_count(), 2u);
  ASSERT_EQ(s.point_lights.size(), 2u);
  EXPECT_EQ(s.point_lights[0].position, Vec3f(1, 2, 3));
  EXPECT_EQ(s.point_lights[0].intensity, Color(10, 20, 30));
  EXPECT_EQ(s.point_lights[1].position, Vec3f(0, 0, 5));
  EXPECT_EQ(s.environment.constant, Color(0.25f, 0.5f, 0.75f));
  EXPECT_EQ(s.emissive_triangle_count(), 0u);
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].position, Vec3f(0, 0, -4));
  EXPECT_EQ(s.cameras[0].target, Vec3f(0.5f, 0.5f, 0));
  EXPECT_EQ(s.cameras[0].up, Vec3f(0, 1, 0));
  EXPECT_FLOAT_EQ(s.cameras[0].vfov_deg, 37.0f);
}

TEST(EcsScene, ViewDirectionIsTakenFromThePosition) {
  SceneFiles files;
  files.write("quad.mtl", kMtl);
  files.write("quad.obj", kQuad);
  // -vd before -vp: the target still follows the final position.
  const Scene s = load_scene(
      files.write("d.ecs", "-i quad.obj -vd 0 0 2 -vp 1 1 -3 -pointlight 0 0 -1 1 1 1\n"));
  EXPECT_EQ(s.cameras[0].target, Vec3f(1, 1, -1));
}

TEST(EcsScene, RefusesWhatItCannotRenderAsEmbreeWould) {
  SceneFiles files;
  files.write("quad.mtl", kMtl);
  files.write("quad.obj", kQuad);
  const auto error = [&](const std::string& name, const std::string& text) {
    return load_error(files.write(name, text));
  };
  EXPECT_THAT(error("xml.ecs", "-i scene.xml\n"), HasSubstr("XML"));
  EXPECT_THAT(error("dir.ecs", "-i quad.obj --dirlight -1 -1 1 3 3 3\n"),
              HasSubstr("'--dirlight' is not supported"));
  EXPECT_THAT(error("hand.ecs", "-i quad.obj --righthanded\n"), HasSubstr("--righthanded"));
  EXPECT_THAT(error("nan.ecs", "-i quad.obj -vp 0 nan 0\n"), HasSubstr("finite"));
  EXPECT_THAT(error("short.ecs", "-i quad.obj -pointlight 0 0 0 1 1\n"), HasSubstr("file ends"));
  EXPECT_THAT(error("neg.ecs", "-i quad.obj -pointlight 0 0 0 1 -1 1\n"), HasSubstr("negative"));
  EXPECT_THAT(error("fov.ecs", "-i quad.obj -fov 180\n"), HasSubstr("fov"));
  EXPECT_THAT(error("none.ecs", "-pointlight 0 0 0 1 1 1\n"), HasSubstr("no -i mesh"));
  EXPECT_THAT(error("self.ecs", "-i quad.obj -vp 1 1 1 -vi 1 1 1\n"), HasSubstr("own position"));
  EXPECT_THAT(error("up.ecs", "-i quad.obj -vp 0 0 -1 -vi 0 0 0 -vu 0 0 1\n"),
              HasSubstr("parallel"));
  EXPECT_THAT(error("gone.ecs", "-i absent.obj\n"), HasSubstr("absent.obj"));
  const std::string e = error("named.ecs", "-i quad.obj -spp 4\n");
  EXPECT_THAT(e, HasSubstr("named.ecs"));
  EXPECT_THAT(e, HasSubstr("'-spp'"));
}

}  // namespace
}  // namespace tuneray
