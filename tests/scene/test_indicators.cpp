// Indicators on scenes with known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/camera_spline.h"
#include "scene/indicators.h"

namespace tuneray {
namespace {

// Unit cube [0,1]^3 as 12 triangles (each of area 1/2), one mesh, Lambert.
Scene unit_cube() {
  Scene s;
  for (int i = 0; i < 8; ++i)
    s.positions.push_back(Vec3f(static_cast<float>(i & 1), static_cast<float>((i >> 1) & 1),
                                static_cast<float>((i >> 2) & 1)));
  s.normals.assign(8, Vec3f(0, 1, 0));
  const uint32_t quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (auto& q : quads) {
    s.triangles.push_back({{q[0], q[1], q[2]}});
    s.triangles.push_back({{q[0], q[2], q[3]}});
  }
  s.material_ids.assign(12, 0);
  s.materials.push_back(Material{});
  s.meshes.push_back({"cube", 0, 12});
  return s;
}

TEST(Indicators, UnitCubeHasItsAnalyticValues) {
  Scene cube = unit_cube();
  CameraDesc cam;
  cam.position = {0.5f, 0.5f, 3.0f};
  cam.target = {0.5f, 0.5f, 0.5f};
  cam.vfov_deg = 60;
  Indicators ind = compute_indicators(cube, cam);
  EXPECT_DOUBLE_EQ(ind[0], 0.0);                 // one mesh
  EXPECT_NEAR(ind[1], std::log10(12.0), 1e-12);  // 12 triangles
  EXPECT_DOUBLE_EQ(ind[2], 0.0);                 // no lights: log10(1 + 0)
  EXPECT_NEAR(ind[3], 0.5, 1e-6);
  EXPECT_NEAR(ind[5], 3.0, 1e-6);  // z = 3 in a box of depth 1 from 0
  EXPECT_NEAR(ind[8], 0.5, 1e-6);
  EXPECT_DOUBLE_EQ(ind[9], 60.0);
  EXPECT_DOUBLE_EQ(ind[10], 1.0);                          // all Lambert
  EXPECT_NEAR(ind[11], std::log10(std::sqrt(3.0)), 1e-6);  // diagonal
  EXPECT_NEAR(ind[12], std::log10(6.0 / 3.0), 1e-6);       // area / diagonal^2
  EXPECT_DOUBLE_EQ(ind[13], -8.0);                         // no emissive area
  EXPECT_NEAR(ind[14], std::log10(2.0), 1e-6);             // one mesh: same as area ratio
  EXPECT_DOUBLE_EQ(ind[15], -20.0);  // equal triangles: zero variance, at the floor
}

TEST(Indicators, TwoMeshesOfKnownAreasAndAnEmitter) {
  Scene s = unit_cube();
  // Second mesh: the cube's triangles scaled by 2 in x/y (areas 2 and 0.5 mixed) — build it as
  // one big triangle of area 2 and one of area 0.5, emissive.
  uint32_t base = static_cast<uint32_t>(s.positions.size());
  s.positions.insert(s.positions.end(), {Vec3f(0, 0, 0), Vec3f(2, 0, 0), Vec3f(0, 2, 0),
                                         Vec3f(0, 0, 1), Vec3f(1, 0, 1), Vec3f(0, 1, 1)});
  s.normals.resize(s.positions.size(), Vec3f(0, 0, 1));
  s.triangles.push_back({{base, base + 1, base + 2}});
  s.triangles.push_back({{base + 3, base + 4, base + 5}});
  Material light;
  light.emission = Color(1.0f);
  s.materials.push_back(light);
  s.material_ids.insert(s.material_ids.end(), {1, 1});
  s.meshes.push_back({"pair", 12, 2});

  SceneIndicators si = compute_scene_indicators(s);
  double diag2 = 4.0 + 4.0 + 1.0;  // box [0,2]x[0,2]x[0,1]
  EXPECT_NEAR(si.diagonal, 3.0, 1e-6);
  EXPECT_DOUBLE_EQ(si.lights, 2.0);
  EXPECT_NEAR(si.area_ratio, (6.0 + 2.5) / diag2, 1e-6);
  EXPECT_NEAR(si.light_area_ratio, 2.5 / diag2, 1e-6);
  EXPECT_NEAR(si.area_per_mesh_ratio, (8.5 / 2) / diag2, 1e-6);
  // Mesh 1 variance 0; mesh 2: areas {2, 0.5}/9, variance ((1.5/9)/2)^2.
  double v2 = std::pow(0.75 / diag2, 2);
  EXPECT_NEAR(si.mesh_area_variance_mean, v2 / 2, 1e-12);
  EXPECT_NEAR(si.mesh_area_variance_variance, std::pow(v2 / 2, 2), 1e-15);
  // Area-weighted diffuseness: the Lambert emitter counts as diffuse too.
  EXPECT_DOUBLE_EQ(si.diffuse_ratio, 1.0);
}

TEST(Indicators, EveryValueOfABuiltinLikeSceneLiesInItsRange) {
  Scene cube = unit_cube();
  CameraDesc cam;
  cam.position = {0.2f, 0.3f, 0.9f};
  Indicators ind = compute_indicators(cube, cam);
  const auto& infos = indicator_infos();
  for (size_t i = 0; i < kIndicatorCount; ++i) {
    EXPECT_GE(ind[i], infos[i].lo) << infos[i].name;
    EXPECT_LE(ind[i], infos[i].hi) << infos[i].name;
  }
}

TEST(CameraSpline, PassesThroughItsKeyframesAndIsContinuous) {
  CameraPath path;
  path.name = "p";
  for (int i = 0; i < 4; ++i) {
    CameraDesc k;
    k.position = {static_cast<float>(i), static_cast<float>(i * i), 0};
    k.target = {0, 0, static_cast<float>(-i)};
    k.vfov_deg = 30.0f + 10.0f * i;
    path.keyframes.push_back(k);
  }
  // 3 segments sampled at 31 points: every 10th sample is a keyframe.
  std::vector<CameraDesc> samples = sample_camera_path(path, 31);
  ASSERT_EQ(samples.size(), 31u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(length(samples[i * 10].position - path.keyframes[i].position), 0.0f, 1e-4f);
    EXPECT_NEAR(samples[i * 10].vfov_deg, path.keyframes[i].vfov_deg, 1e-4f);
  }
  for (size_t i = 1; i < samples.size(); ++i)  // no jumps: steps stay small
    EXPECT_LT(length(samples[i].position - samples[i - 1].position), 1.5f);
  EXPECT_THROW(sample_camera_path(CameraPath{}, 10), std::invalid_argument);
}

TEST(CameraSpline, CamerasAlongPathFollowTheScenesPathOrTheAutomaticOne) {
  Scene cube = unit_cube();
  // No path of its own: path 0 is the automatic one, any other is an error.
  const std::vector<CameraDesc> automatic = cameras_along_path(cube, 0, 7);
  const std::vector<CameraDesc> expected = sample_camera_path(automatic_camera_path(cube), 7);
  ASSERT_EQ(automatic.size(), 7u);
  for (size_t i = 0; i < automatic.size(); ++i)
    EXPECT_EQ(automatic[i].position, expected[i].position) << i;
  EXPECT_THROW(cameras_along_path(cube, 1, 7), std::invalid_argument);
  EXPECT_THROW(cameras_along_path(cube, -1, 7), std::invalid_argument);
  EXPECT_THROW(cameras_along_path(cube, 0, 0), std::invalid_argument);
  // With two paths, index 1 is the second one, ends included.
  for (int p = 0; p < 2; ++p) {
    CameraPath path;
    path.name = p == 0 ? "first" : "second";
    for (int i = 0; i < 2; ++i) {
      CameraDesc k;
      k.position = {static_cast<float>(10 * p + i), 2, 3};
      path.keyframes.push_back(k);
    }
    cube.camera_paths.push_back(path);
  }
  const std::vector<CameraDesc> second = cameras_along_path(cube, 1, 3);
  ASSERT_EQ(second.size(), 3u);
  EXPECT_EQ(second.front().position, Vec3f(10, 2, 3));
  EXPECT_EQ(second.back().position, Vec3f(11, 2, 3));
  EXPECT_THROW(cameras_along_path(cube, 2, 3), std::invalid_argument);
}

TEST(CameraSpline, AutomaticPathGoesBothCloseAndFar) {
  Scene cube = unit_cube();
  CameraPath path = automatic_camera_path(cube);
  BBox b = cube.bounds();
  float r = 0.5f * b.diagonal();
  float nearest = kInf, farthest = 0;
  for (const CameraDesc& c : sample_camera_path(path, 100)) {
    float d = length(c.position - b.center());
    nearest = std::min(nearest, d);
    farthest = std::max(farthest, d);
  }
  EXPECT_LT(nearest, 0.5f * r);
  EXPECT_GT(farthest, 2.0f * r);
}

}  // namespace
}  // namespace tuneray
