#include <gtest/gtest.h>

#include "scene/load.h"
#include "scene/stats.h"
#include "scene_files.h"

namespace tuneray {
namespace {

TEST(Stats, CountsAreasAndLights) {
  testing::SceneFiles files;
  files.write("s.mtl", "newmtl lamp\nKe 1 1 1\nnewmtl wall\nKd 0.5 0.5 0.5\n");
  std::string obj = files.write("s.obj",
                                "mtllib s.mtl\nv 0 0 0\nv 2 0 0\nv 2 3 0\nv 0 3 0\n"
                                "g a\nusemtl lamp\nf 1 2 3\ng b\nusemtl wall\nf 1 3 4\n");
  Scene s = load_scene(obj);
  SceneStats st = compute_stats(s);
  EXPECT_EQ(st.triangles, 2u);
  EXPECT_EQ(st.vertices, 4u);
  EXPECT_EQ(st.meshes, 2u);
  EXPECT_EQ(st.materials, 2u);
  EXPECT_EQ(st.textures, 0u);
  EXPECT_EQ(st.emissive_triangles, 1u);
  EXPECT_EQ(st.lights, 1u);
  EXPECT_FALSE(st.environment);
  EXPECT_DOUBLE_EQ(st.surface_area, 6.0);
  EXPECT_DOUBLE_EQ(st.emissive_area, 3.0);
  EXPECT_EQ(st.bounds.hi, Vec3f(2, 3, 0));
  EXPECT_GE(st.memory_bytes, 4 * sizeof(Vec3f) * 2 + 2 * sizeof(Triangle));
}

}  // namespace
}  // namespace tuneray
