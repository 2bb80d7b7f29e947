#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scene/load.h"
#include "scene/normals.h"
#include "scene/stats.h"

namespace tuneray {
namespace {

struct Expected {
  const char* name;
  size_t triangles;
};

class Builtins : public ::testing::TestWithParam<Expected> {};

TEST_P(Builtins, TriangleCountIsStable) {
  EXPECT_EQ(load_scene(GetParam().name).triangles.size(), GetParam().triangles);
}

TEST_P(Builtins, GeometryIsWellFormed) {
  Scene s = load_scene(GetParam().name);
  ASSERT_EQ(s.normals.size(), s.positions.size());
  for (Vec3f n : s.normals) ASSERT_NEAR(length(n), 1.0f, 1e-5f);
  ASSERT_EQ(s.material_ids.size(), s.triangles.size());
  for (uint32_t id : s.material_ids) ASSERT_LT(id, s.materials.size());
  // Front faces (counter-clockwise winding) agree with the shading normals.
  for (const Triangle& t : s.triangles) {
    Vec3f n = area_normal(s.positions[t.v[0]], s.positions[t.v[1]], s.positions[t.v[2]]);
    ASSERT_GT(length(n), 0.0f);
    for (uint32_t v : t.v) ASSERT_GT(dot(n, s.normals[v]), 0.0f);
  }
  uint32_t covered = 0;
  for (const MeshRange& m : s.meshes) {
    EXPECT_EQ(m.first, covered);
    covered += m.count;
  }
  EXPECT_EQ(covered, s.triangles.size());
}

TEST_P(Builtins, HasCameraPathLightAndNoNotes) {
  Scene s = load_scene(GetParam().name);
  EXPECT_FALSE(s.cameras.empty());
  ASSERT_FALSE(s.camera_paths.empty());
  EXPECT_GE(s.camera_paths[0].keyframes.size(), 4u);
  EXPECT_GT(compute_stats(s).lights, 0u);
  EXPECT_TRUE(s.notes.empty());  // built-ins light and frame themselves
}

INSTANTIATE_TEST_SUITE_P(All, Builtins,
                         ::testing::Values(Expected{"cornell", 36}, Expected{"voxels", 25644},
                                           Expected{"mixed", 100016}, Expected{"furnace", 20480},
                                           Expected{"furnace_ggx", 20480}, Expected{"sky", 26626}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(BuiltinNames, ListsEveryBuiltinAndCornellFirst) {
  std::vector<std::string> names = builtin_scene_names();
  ASSERT_EQ(names.size(), 6u);
  EXPECT_EQ(names[0], "cornell");
}

TEST(BuiltinCornell, LayoutAndLight) {
  Scene s = load_scene("cornell");
  BBox b = s.bounds();
  EXPECT_EQ(b.lo, Vec3f(0.0f));
  EXPECT_EQ(b.hi, Vec3f(1.0f));
  SceneStats st = compute_stats(s);
  EXPECT_EQ(st.emissive_triangles, 2u);
  EXPECT_NEAR(st.emissive_area, 0.04, 1e-6);
  EXPECT_FALSE(s.environment.active());
}

TEST(BuiltinFurnace, UnitSphereInUniformLight) {
  for (const char* name : {"furnace", "furnace_ggx"}) {
    Scene s = load_scene(name);
    for (Vec3f p : s.positions) ASSERT_NEAR(length(p), 1.0f, 1e-5f);
    EXPECT_EQ(s.environment.constant, Color(1.0f));
    EXPECT_FLOAT_EQ(s.environment.scale, 1.0f);
    EXPECT_TRUE(s.point_lights.empty());
    EXPECT_EQ(s.emissive_triangle_count(), 0u);
    ASSERT_EQ(s.materials.size(), 1u);
  }
  Scene lambert = load_scene("furnace");
  EXPECT_EQ(lambert.materials[0].name, "diffuse");
  EXPECT_EQ(lambert.materials[0].type, MaterialType::kLambert);
  EXPECT_EQ(lambert.materials[0].base_color, Color(1.0f));
  Scene ggx = load_scene("furnace_ggx");
  EXPECT_EQ(ggx.materials[0].type, MaterialType::kGlossy);
  EXPECT_EQ(ggx.materials[0].specular_color, Color(1.0f));
  EXPECT_FLOAT_EQ(ggx.materials[0].roughness_u, 0.5f);
  EXPECT_FLOAT_EQ(ggx.materials[0].roughness_v, 0.5f);
}

TEST(BuiltinVoxels, AllTrianglesAreHalfUnitAxisAligned) {
  Scene s = load_scene("voxels");
  EXPECT_GE(s.triangles.size(), 20000u);
  EXPECT_LE(s.triangles.size(), 50000u);
  for (const Triangle& t : s.triangles) {
    Vec3f n = area_normal(s.positions[t.v[0]], s.positions[t.v[1]], s.positions[t.v[2]]);
    ASSERT_FLOAT_EQ(length(n), 1.0f);  // area 1/2
    ASSERT_FLOAT_EQ(max_component(Vec3f(std::abs(n.x), std::abs(n.y), std::abs(n.z))), 1.0f);
  }
  EXPECT_EQ(s.point_lights.size(), 1u);
  EXPECT_TRUE(s.environment.active());
}

TEST(BuiltinMixed, TinyAndHugeTriangles) {
  Scene s = load_scene("mixed");
  double smallest = 1e30, largest = 0;
  for (const Triangle& t : s.triangles) {
    double a =
        0.5 * length(area_normal(s.positions[t.v[0]], s.positions[t.v[1]], s.positions[t.v[2]]));
    smallest = std::min(smallest, a);
    largest = std::max(largest, a);
  }
  EXPECT_GT(largest / smallest, 1e8);
  EXPECT_GT(s.emissive_triangle_count(), 0u);
  // Nothing sinks into the floor.
  for (Vec3f p : s.positions) ASSERT_GE(p.y, 0.0f);
}

// The environment-map scene: an HDR equirectangular sky whose sun is the brightest thing in it,
// seamless at u = 0 (the clouds' noise wraps), and one object of every material type.
TEST(BuiltinSky, HdrSkyWithASunAndEveryMaterialType) {
  Scene s = load_scene("sky");
  const Image& map = s.environment.map;
  ASSERT_EQ(map.width(), 1024);
  ASSERT_EQ(map.height(), 512);
  float brightest = 0, sky_mean = 0;
  for (int y = 0; y < map.height(); ++y)
    for (int x = 0; x < map.width(); ++x) {
      Color c = map.at(x, y);
      ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
      ASSERT_GE(min_component(c), 0.0f);
      brightest = std::max(brightest, max_component(c));
      sky_mean += luminance(c) / static_cast<float>(map.width() * map.height());
    }
  EXPECT_GT(brightest, 100 * sky_mean);  // a sun: importance sampling has something to find
  // Across the seam the sky changes no more than between any two neighbouring columns.
  auto difference = [](Color a, Color b) {
    return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)});
  };
  float seam = 0, inner = 0;
  for (int y = 0; y < map.height() / 2; ++y) {
    seam = std::max(seam, difference(map.at(0, y), map.at(map.width() - 1, y)));
    inner = std::max(inner, difference(map.at(0, y), map.at(1, y)));
  }
  EXPECT_LT(seam, 2 * inner + 1e-3f);
  std::vector<bool> seen(5, false);
  for (const Material& m : s.materials) seen[static_cast<int>(m.type)] = true;
  for (size_t t = 0; t < seen.size(); ++t) EXPECT_TRUE(seen[t]) << "material type " << t;
  EXPECT_TRUE(s.point_lights.empty());
  EXPECT_EQ(s.emissive_triangle_count(), 0u);
}

}  // namespace
}  // namespace tuneray
