#include <gtest/gtest.h>

#include <cmath>

#include "scene/load.h"
#include "scene/mtl_material.h"
#include "scene_files.h"

namespace tuneray {
namespace {

MtlParams params(int illum, Color ks = Color(0.0f), float ns = 10.0f) {
  MtlParams p;
  p.kd = Color(0.5f, 0.4f, 0.3f);
  p.ks = ks;
  p.ns = ns;
  p.illum = illum;
  return p;
}

TEST(MtlMaterial, ShininessToRoughness) {
  EXPECT_FLOAT_EQ(roughness_from_shininess(0.0f), 1.0f);
  EXPECT_FLOAT_EQ(roughness_from_shininess(6.0f), 0.5f);  // sqrt(2 / 8)
  EXPECT_FLOAT_EQ(roughness_from_shininess(198.0f), 0.1f);
  EXPECT_FLOAT_EQ(roughness_from_shininess(1e9f), kMinRoughness);
  EXPECT_FLOAT_EQ(roughness_from_shininess(-5.0f), 1.0f);
}

TEST(MtlMaterial, IllumModels) {
  EXPECT_EQ(material_from_mtl(params(0)).type, MaterialType::kLambert);
  EXPECT_EQ(material_from_mtl(params(1, Color(0.5f))).type, MaterialType::kLambert);
  EXPECT_EQ(material_from_mtl(params(2)).type, MaterialType::kLambert);
  EXPECT_EQ(material_from_mtl(params(2, Color(0.2f))).type, MaterialType::kPrincipled);
  EXPECT_EQ(material_from_mtl(params(3)).type, MaterialType::kLambert);
  EXPECT_EQ(material_from_mtl(params(3, Color(0.9f), 500)).type, MaterialType::kGlossy);
  EXPECT_EQ(material_from_mtl(params(3, Color(0.9f), 1000)).type, MaterialType::kMirror);
  for (int illum : {4, 6, 7, 9})
    EXPECT_EQ(material_from_mtl(params(illum)).type, MaterialType::kDielectric) << illum;
  EXPECT_EQ(material_from_mtl(params(5)).type, MaterialType::kMirror);
  MtlParams transparent = params(2, Color(0.2f));
  transparent.dissolve = 0.5f;
  EXPECT_EQ(material_from_mtl(transparent).type, MaterialType::kDielectric);
}

TEST(MtlMaterial, MirrorWithoutKsIsWhite) {
  EXPECT_EQ(material_from_mtl(params(5)).specular_color, Color(1.0f));
  EXPECT_EQ(material_from_mtl(params(5, Color(0.3f))).specular_color, Color(0.3f));
}

TEST(MtlMaterial, Anisotropy) {
  MtlParams p = params(3, Color(0.9f), 6.0f);  // alpha 0.5
  p.aniso = 1.0f;
  Material m = material_from_mtl(p);
  const float aspect = std::sqrt(0.1f);
  EXPECT_FLOAT_EQ(m.roughness_u, 0.5f / aspect > 1.0f ? 1.0f : 0.5f / aspect);
  EXPECT_FLOAT_EQ(m.roughness_v, 0.5f * aspect);
  p.aniso = 0.0f;
  m = material_from_mtl(p);
  EXPECT_FLOAT_EQ(m.roughness_u, 0.5f);
  EXPECT_FLOAT_EQ(m.roughness_v, 0.5f);
}

// The same mapping end to end through tinyobjloader's MTL parser.
TEST(MtlMaterial, ValuesFromAnMtlFile) {
  testing::SceneFiles files;
  files.write("v.mtl",
              "newmtl plastic\nKd 0.1 0.2 0.3\nKs 0.04 0.05 0.06\nNs 198\nillum 2\n"
              "newmtl glass\nKd 0 0 0\nNi 1.33\nTf 0.9 0.8 0.7\nillum 7\n"
              "newmtl faded\nKd 1 1 1\nd 0.4\nillum 2\n"
              "newmtl brushed\nKs 1 0.8 0.6\nNs 6\naniso 0.5\nillum 3\n"
              "newmtl lamp\nKd 0 0 0\nKe 10 20 30\nillum 1\n"
              "newmtl oldglass\nTr 0.25\nillum 2\n");
  std::string body = "mtllib v.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const char* name : {"plastic", "glass", "faded", "brushed", "lamp", "oldglass"})
    body += std::string("usemtl ") + name + "\nf 1 2 3\n";
  Scene s = load_scene(files.write("v.obj", body));
  ASSERT_EQ(s.materials.size(), 6u);
  const Material& plastic = s.materials[0];
  EXPECT_EQ(plastic.type, MaterialType::kPrincipled);
  EXPECT_EQ(plastic.base_color, Color(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(plastic.specular_color, Color(0.04f, 0.05f, 0.06f));
  EXPECT_FLOAT_EQ(plastic.roughness_u, 0.1f);
  EXPECT_FLOAT_EQ(plastic.roughness_v, 0.1f);
  const Material& glass = s.materials[1];
  EXPECT_EQ(glass.type, MaterialType::kDielectric);
  EXPECT_FLOAT_EQ(glass.ior, 1.33f);
  EXPECT_EQ(glass.transmittance, Color(0.9f, 0.8f, 0.7f));
  const Material& faded = s.materials[2];
  EXPECT_EQ(faded.type, MaterialType::kDielectric);
  EXPECT_FLOAT_EQ(faded.ior, kDefaultDielectricIor);  // Ni absent
  EXPECT_EQ(faded.transmittance, Color(1.0f));        // Tf absent
  const Material& brushed = s.materials[3];
  EXPECT_EQ(brushed.type, MaterialType::kGlossy);
  const float aspect = std::sqrt(1.0f - 0.45f);
  EXPECT_FLOAT_EQ(brushed.roughness_u, 0.5f / aspect);
  EXPECT_FLOAT_EQ(brushed.roughness_v, 0.5f * aspect);
  EXPECT_EQ(s.materials[4].emission, Color(10, 20, 30));
  EXPECT_TRUE(s.materials[4].is_emissive());
  EXPECT_EQ(s.materials[5].type, MaterialType::kDielectric);  // Tr 0.25 = d 0.75
}

}  // namespace
}  // namespace tuneray
