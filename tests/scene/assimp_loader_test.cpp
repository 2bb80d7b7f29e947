#include <gtest/gtest.h>

#include <cstring>

#include "scene/load.h"
#include "scene_files.h"

namespace tuneray {
namespace {

TEST(AssimpLoader, AsciiPlyQuad) {
  testing::SceneFiles files;
  std::string ply = files.write("quad.ply",
                                "ply\nformat ascii 1.0\nelement vertex 4\n"
                                "property float x\nproperty float y\nproperty float z\n"
                                "element face 1\nproperty list uchar int vertex_indices\n"
                                "end_header\n0 0 0\n2 0 0\n2 0 -3\n0 0 -3\n4 0 1 2 3\n");
  Scene s = load_scene(ply);
  ASSERT_EQ(s.triangles.size(), 2u);
  ASSERT_EQ(s.positions.size(), 4u);
  // Counter-clockwise seen from above: generated normals point up.
  for (Vec3f n : s.normals) {
    EXPECT_NEAR(n.x, 0.0f, 1e-6f);
    EXPECT_NEAR(n.y, 1.0f, 1e-6f);
    EXPECT_NEAR(n.z, 0.0f, 1e-6f);
  }
  BBox b = s.bounds();
  EXPECT_EQ(b.lo, Vec3f(0, 0, -3));
  EXPECT_EQ(b.hi, Vec3f(2, 0, 0));
  ASSERT_FALSE(s.materials.empty());
  EXPECT_TRUE(s.environment.active());  // no lights of its own
}

// Binary little-endian PLY of one triangle; `last_index` is the third vertex index and
// `cut` bytes are dropped from the end.
std::string binary_ply(int32_t last_index, size_t cut = 0) {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  s.append(reinterpret_cast<const char*>(v), sizeof v);
  s.push_back(3);
  const int32_t idx[3] = {0, 1, last_index};
  s.append(reinterpret_cast<const char*>(idx), sizeof idx);
  s.resize(s.size() - cut);
  return s;
}

TEST(AssimpLoader, BinaryPly) {
  testing::SceneFiles files;
  Scene s = load_scene(files.write("ok.ply", binary_ply(2)));
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.bounds().hi, Vec3f(1, 1, 0));
}

TEST(AssimpLoader, TruncatedOrOutOfRangeBinaryPlyIsAnErrorNotACrash) {
  testing::SceneFiles files;
  using ::testing::HasSubstr;
  EXPECT_THAT(testing::load_error(files.write("short.ply", binary_ply(2, 5))),
              HasSubstr("short.ply: malformed PLY: file ends inside element 'face'"));
  EXPECT_THAT(testing::load_error(files.write("range.ply", binary_ply(7))),
              HasSubstr("range.ply: malformed PLY: face 0 has a vertex index out of range"));
  EXPECT_THAT(testing::load_error(files.write("neg.ply", binary_ply(-1))),
              HasSubstr("out of range"));
}

// Found by fuzz/fuzz_mesh: assimp read this ASCII header and leaked.
TEST(AssimpLoader, MangledPlyHeaderLinesAreRefused) {
  testing::SceneFiles files;
  using ::testing::HasSubstr;
  const std::string tail =
      "property float x\nproperty float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_THAT(
      testing::load_error(
          files.write("extra.ply", "ply\nformat ascii 1.0\nelement vertex 3 junk\n" + tail)),
      HasSubstr(
          "extra.ply: malformed PLY: unexpected 'junk' in header line 'element vertex 3 junk'"));
  EXPECT_THAT(testing::load_error(
                  files.write("keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 3\n" + tail)),
              HasSubstr("keyword.ply: malformed PLY: unknown header line 'elemnt vertex 3'"));
  // Found by fuzz/fuzz_mesh: assimp never returned from this one.
  EXPECT_THAT(testing::load_error(files.write(
                  "end.ply", "ply\nformat ascii 1.0\nelement vertex 3\n" +
                                 tail.substr(0, tail.find("end_header")) + "end_headerssss\n" +
                                 tail.substr(tail.find("end_header") + 11))),
              HasSubstr("end.ply: malformed PLY: bad end_header line 'end_headerssss'"));
  // Comments, obj_info and CRLF line ends are fine.
  Scene s =
      load_scene(files.write("ok.ply",
                             "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nobj_info x\r\n"
                             "element vertex 3\r\n" +
                                 tail));
  EXPECT_EQ(s.triangles.size(), 1u);
}

// Found by fuzz/fuzz_mesh: assimp leaked on short or mangled ASCII bodies.
TEST(AssimpLoader, ShortOrMangledAsciiPlyBodiesAreRefused) {
  testing::SceneFiles files;
  using ::testing::HasSubstr;
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_THAT(testing::load_error(files.write("short.ply", header + "0 0 0\n1 0 0\n0 1\n")),
              HasSubstr("short.ply: malformed PLY: file ends inside element 'vertex' 2"));
  EXPECT_THAT(
      testing::load_error(files.write("mangled.ply", header + "0 0 0\n1 0 0\n0 1 0\n3$0 1 2\n")),
      HasSubstr("mangled.ply: malformed PLY: '3$0' is not a number (element 'face' 0)"));
  EXPECT_THAT(
      testing::load_error(files.write("range.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")),
      HasSubstr("range.ply: malformed PLY: face 0 has a vertex index out of range"));
}

// Found by fuzz/fuzz_mesh: assimp leaked on GLB containers with wrong lengths.
TEST(AssimpLoader, MalformedGlbAndGltfAreRefused) {
  testing::SceneFiles files;
  using ::testing::HasSubstr;
  std::string glb("glTF\x02\x00\x00\x00\xff\x00\x00\x00", 12);
  glb += std::string("\x04\x00\x00\x00JSON{}  ", 12);
  EXPECT_THAT(testing::load_error(files.write("len.glb", glb)),
              HasSubstr("len.glb: malformed glTF: GLB header says 255 bytes, the file has 24"));
  EXPECT_THAT(testing::load_error(files.write("text.gltf", "{\"asset\": ")),
              HasSubstr("text.gltf: malformed glTF: the JSON does not parse"));
  EXPECT_THAT(testing::load_error(files.write("array.gltf", "[1, 2]")),
              HasSubstr("array.gltf: malformed glTF: the JSON is not an object"));
}

TEST(AssimpLoader, GltfTriangleWithEmission) {
  testing::SceneFiles files;
  // One triangle; positions as base64 little-endian floats (0,0,0) (1,0,0) (0,1,0).
  std::string gltf = files.write("tri.gltf", R"({
    "asset": {"version": "2.0"},
    "scenes": [{"nodes": [0]}], "scene": 0,
    "nodes": [{"mesh": 0, "translation": [0, 0, 5]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
    "materials": [{"name": "glow", "emissiveFactor": [1, 0.5, 0.25],
                   "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.3, 0.4, 1]}}],
    "buffers": [{"byteLength": 36,
      "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}]
  })");
  Scene s = load_scene(gltf);
  ASSERT_EQ(s.triangles.size(), 1u);
  EXPECT_EQ(s.bounds().hi, Vec3f(1, 1, 5));  // node transform baked in
  const Material& m = s.materials[s.material_ids[0]];
  EXPECT_EQ(m.emission, Color(1, 0.5f, 0.25f));
  EXPECT_NEAR(m.base_color.x, 0.2f, 1e-6f);
  EXPECT_NEAR(m.base_color.z, 0.4f, 1e-6f);
  EXPECT_EQ(s.emissive_triangle_count(), 1u);
}

}  // namespace
}  // namespace tuneray
