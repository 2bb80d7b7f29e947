#include <gtest/gtest.h>

#include <cmath>

#include "image/io.h"
#include "scene/load.h"
#include "scene_files.h"

namespace tuneray {
namespace {

using testing::SceneFiles;

void expect_vec_near(Vec3f a, Vec3f b, float tol = 1e-6f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(ObjLoader, FlatQuadWithoutNormalsGetsTheFaceNormal) {
  SceneFiles files;
  // A tilted quad in the plane x + z = 1, counter-clockwise seen from (1, 0, 1).
  std::string obj = files.write("quad.obj",
                                "v 1 0 0\nv 0 0 1\nv 0 1 1\nv 1 1 0\n"
                                "f 1 4 3 2\n");
  Scene s = load_scene(obj);
  ASSERT_EQ(s.triangles.size(), 2u);
  ASSERT_EQ(s.normals.size(), 4u);
  const Vec3f face = normalize(Vec3f(1, 0, 1));
  for (Vec3f n : s.normals) expect_vec_near(n, face);
  EXPECT_TRUE(s.uvs.empty());
}

TEST(ObjLoader, CubeCornerNormalIsTheDiagonal) {
  SceneFiles files;
  // Unit cube; the origin (vertex 1) comes first in each of its three faces, so fan
  // triangulation gives it the full area of each: its normal is exactly -(1,1,1)/sqrt(3).
  std::string obj = files.write("cube.obj",
                                "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                                "f 1 4 3 2\n"    // z = 0, normal -z
                                "f 1 2 6 5\n"    // y = 0, normal -y
                                "f 1 5 8 4\n"    // x = 0, normal -x
                                "f 7 8 5 6\n"    // z = 1
                                "f 7 3 4 8\n"    // y = 1
                                "f 7 6 2 3\n");  // x = 1
  Scene s = load_scene(obj);
  ASSERT_EQ(s.triangles.size(), 12u);
  ASSERT_EQ(s.positions.size(), 8u);  // shared positions are welded, not split per face
  const float k = 1.0f / std::sqrt(3.0f);
  expect_vec_near(s.normals[0], Vec3f(-k, -k, -k));
  // Vertex 7 (1,1,1) likewise leads its three faces.
  for (size_t i = 0; i < s.positions.size(); ++i)
    if (s.positions[i] == Vec3f(1, 1, 1)) expect_vec_near(s.normals[i], Vec3f(k, k, k));
}

TEST(ObjLoader, FileNormalsAreUsedAndNormalised) {
  SceneFiles files;
  std::string obj = files.write("tri.obj",
                                "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nvn 0 3 0\n"
                                "f 1//1 2//1 3//2\n");
  Scene s = load_scene(obj);
  ASSERT_EQ(s.normals.size(), 3u);
  expect_vec_near(s.normals[0], Vec3f(0, 0, 1));
  expect_vec_near(s.normals[2], Vec3f(0, 1, 0));
}

TEST(ObjLoader, VerticesAreSplitPerPositionNormalUvTriple) {
  SceneFiles files;
  // Two triangles share positions 1 and 3, but with different uvs at position 3.
  std::string obj = files.write("split.obj",
                                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                "vt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5\n"
                                "f 1/1 2/2 3/3\nf 2/2 4/1 3/4\n");
  Scene s = load_scene(obj);
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.positions.size(), 5u);
  ASSERT_EQ(s.uvs.size(), 5u);
  EXPECT_EQ(s.triangles[0].v[1], s.triangles[1].v[0]);  // same (position, uv): welded
  EXPECT_NE(s.triangles[0].v[2], s.triangles[1].v[2]);  // same position, other uv: split
  EXPECT_FLOAT_EQ(s.uvs[s.triangles[1].v[2]].x, 0.5f);
  // Without file normals the split vertices still share one smooth normal.
  expect_vec_near(s.normals[s.triangles[0].v[2]], s.normals[s.triangles[1].v[2]]);
}

TEST(ObjLoader, PolygonsAreFanTriangulatedAndGroupsBecomeMeshes) {
  SceneFiles files;
  std::string obj = files.write("poly.obj",
                                "v 0 0 0\nv 1 0 0\nv 2 1 0\nv 1 2 0\nv 0 1 0\n"
                                "g pentagon\nf 1 2 3 4 5\n"
                                "g triangle\nf 1 2 3\n");
  Scene s = load_scene(obj);
  ASSERT_EQ(s.triangles.size(), 4u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(s.triangles[k].v[0], s.triangles[0].v[0]);
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "pentagon");
  EXPECT_EQ(s.meshes[0].count, 3u);
  EXPECT_EQ(s.meshes[1].name, "triangle");
  EXPECT_EQ(s.meshes[1].first, 3u);
  EXPECT_EQ(s.meshes[1].count, 1u);
}

TEST(ObjLoader, PerFaceMaterialsFromMtl) {
  SceneFiles files;
  files.write("m.mtl",
              "newmtl red\nKd 1 0 0\nillum 1\n"
              "newmtl lamp\nKd 0 0 0\nKe 5 4 3\nillum 1\n");
  std::string obj = files.write("m.obj",
                                "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                "usemtl red\nf 1 2 3\nusemtl lamp\nf 2 4 3\n");
  Scene s = load_scene(obj);
  ASSERT_EQ(s.material_ids.size(), 2u);
  EXPECT_EQ(s.materials[s.material_ids[0]].name, "red");
  EXPECT_EQ(s.materials[s.material_ids[1]].name, "lamp");
  EXPECT_EQ(s.emissive_triangle_count(), 1u);
  EXPECT_FALSE(s.environment.active());  // it has a light: no default sky
}

TEST(ObjLoader, NoLightsGetsDefaultSkyAndAutomaticCameraWithNotes) {
  SceneFiles files;
  std::string obj = files.write("tri.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1 2 3\n");
  Scene s = load_scene(obj);
  EXPECT_TRUE(s.environment.active());
  EXPECT_EQ(s.environment.constant, Color(1.0f));
  ASSERT_EQ(s.cameras.size(), 1u);
  // The camera looks at the box centre from a distance where the bounding sphere fits 45°.
  const Vec3f centre(1, 1, 0);
  const float radius = 0.5f * std::sqrt(8.0f);
  expect_vec_near(s.cameras[0].target, centre);
  EXPECT_NEAR(length(s.cameras[0].position - centre), radius / std::sin(22.5f * kPi / 180), 1e-5);
  EXPECT_FLOAT_EQ(s.cameras[0].vfov_deg, 45.0f);
  EXPECT_THAT(s.notes, ::testing::Contains("no lights: added a constant sky of radiance 1"));
  EXPECT_THAT(s.notes, ::testing::Contains("automatic camera framing the bounding box"));
  ASSERT_EQ(s.camera_paths.size(), 1u);
  EXPECT_GE(s.camera_paths[0].keyframes.size(), 4u);
}

TEST(ObjLoader, TexturesAreLoadedLinearAndDeduplicated) {
  SceneFiles files;
  Image image(2, 1);
  image.at(0, 0) = Color(0.5f, 0.25f, 1.0f);
  image.at(1, 0) = Color(0.0f, 1.0f, 0.1f);
  std::filesystem::create_directories(files.path("tex"));
  write_image(files.path("tex/wood.png"), image);
  files.write("t.mtl",
              "newmtl a\nKd 1 1 1\nmap_Kd tex/wood.png\n"
              "newmtl b\nKd 0.5 0.5 0.5\nmap_Kd tex/../tex/wood.png\n");
  std::string obj = files.write("t.obj",
                                "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                "usemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 2/2\n");
  Scene s = load_scene(obj);
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.materials[0].base_texture, 0);
  EXPECT_EQ(s.materials[1].base_texture, 0);
  const Image& t = s.textures[0].image;
  ASSERT_EQ(t.width(), 2);
  // 8-bit sRGB round trip: within one code value of the linear original.
  expect_vec_near(t.at(0, 0), Color(0.5f, 0.25f, 1.0f), 0.01f);
  expect_vec_near(t.at(1, 0), Color(0.0f, 1.0f, 0.1f), 0.01f);
}

}  // namespace
}  // namespace tuneray
