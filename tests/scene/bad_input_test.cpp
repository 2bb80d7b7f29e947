#include <gtest/gtest.h>

#include "scene/load.h"
#include "scene_files.h"

namespace tuneray {
namespace {

using ::testing::HasSubstr;
using testing::load_error;
using testing::SceneFiles;

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

TEST(BadInput, MissingFile) {
  SceneFiles files;
  std::string path = files.path("absent.obj");
  EXPECT_THAT(load_error(path), HasSubstr(path));
}

TEST(BadInput, MalformedFaceIndexZero) {
  SceneFiles files;
  std::string obj = files.write("zero.obj", std::string(kTriangle) + "f 0 1 2\n");
  std::string e = load_error(obj);
  EXPECT_THAT(e, HasSubstr("zero.obj"));
  EXPECT_THAT(e, HasSubstr("malformed"));
}

TEST(BadInput, FaceWithTwoVertices) {
  SceneFiles files;
  std::string obj = files.write("two.obj", std::string(kTriangle) + "f 1 2 3\nf 1 2\n");
  EXPECT_THAT(load_error(obj), HasSubstr("two.obj"));
}

TEST(BadInput, FaceIndexOutOfRange) {
  SceneFiles files;
  std::string obj = files.write("range.obj", std::string(kTriangle) + "f 1 2 7\n");
  std::string e = load_error(obj);
  EXPECT_THAT(e, HasSubstr("range.obj"));
  EXPECT_THAT(e, HasSubstr("out of range"));
}

TEST(BadInput, NegativeRelativeIndexOutOfRange) {
  SceneFiles files;
  std::string obj = files.write("neg.obj", std::string(kTriangle) + "f -1 -2 -4\n");
  EXPECT_THAT(load_error(obj), HasSubstr("out of range"));
}

TEST(BadInput, NormalIndexOutOfRange) {
  SceneFiles files;
  std::string obj = files.write("vn.obj", std::string(kTriangle) + "vn 0 0 1\nf 1//1 2//1 3//2\n");
  EXPECT_THAT(load_error(obj), HasSubstr("normal index 2 out of range"));
}

TEST(BadInput, NonFiniteVertex) {
  SceneFiles files;
  // tinyobjloader reads an overflowing literal as infinity (it maps "nan" to 0).
  std::string obj = files.write("inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n");
  std::string e = load_error(obj);
  EXPECT_THAT(e, HasSubstr("inf.obj"));
  EXPECT_THAT(e, HasSubstr("vertex 2"));
}

TEST(BadInput, EmptyFileAndNoTriangles) {
  SceneFiles files;
  EXPECT_THAT(load_error(files.write("empty.obj", "")), HasSubstr("empty.obj: no triangles"));
  EXPECT_THAT(load_error(files.write("points.obj", kTriangle)),
              HasSubstr("points.obj: no triangles"));
}

TEST(BadInput, MissingMtl) {
  SceneFiles files;
  std::string obj =
      files.write("nomtl.obj", std::string("mtllib gone.mtl\n") + kTriangle + "f 1 2 3\n");
  std::string e = load_error(obj);
  EXPECT_THAT(e, HasSubstr("nomtl.obj"));
  EXPECT_THAT(e, HasSubstr("gone.mtl"));
}

TEST(BadInput, MissingTexture) {
  SceneFiles files;
  files.write("tex.mtl", "newmtl a\nKd 1 1 1\nmap_Kd nowhere.png\n");
  std::string obj =
      files.write("tex.obj", std::string("mtllib tex.mtl\n") + kTriangle + "usemtl a\nf 1 2 3\n");
  std::string e = load_error(obj);
  EXPECT_THAT(e, HasSubstr("tex.mtl"));
  EXPECT_THAT(e, HasSubstr("nowhere.png"));
}

TEST(BadInput, CorruptTexture) {
  SceneFiles files;
  files.write("bad.png", "this is not a png");
  files.write("tex.mtl", "newmtl a\nKd 1 1 1\nmap_Kd bad.png\n");
  std::string obj =
      files.write("tex.obj", std::string("mtllib tex.mtl\n") + kTriangle + "usemtl a\nf 1 2 3\n");
  EXPECT_THAT(load_error(obj), HasSubstr("bad.png"));
}

TEST(BadInput, UnknownExtension) {
  SceneFiles files;
  std::string path = files.write("scene.xyz", "whatever");
  std::string e = load_error(path);
  EXPECT_THAT(e, HasSubstr("scene.xyz"));
  EXPECT_THAT(e, HasSubstr("unknown scene file extension"));
  EXPECT_THAT(load_error("not_a_builtin"), HasSubstr("not_a_builtin"));
}

TEST(BadInput, ExtensionIsCaseInsensitive) {
  SceneFiles files;
  std::string obj = files.write("upper.OBJ", std::string(kTriangle) + "f 1 2 3\n");
  EXPECT_EQ(load_error(obj), "");
}

TEST(BadInput, MalformedPly) {
  SceneFiles files;
  std::string ply = files.write("broken.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  EXPECT_THAT(load_error(ply), HasSubstr("broken.ply"));
}

}  // namespace
}  // namespace tuneray
