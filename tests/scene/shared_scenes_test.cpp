// The staged real scenes in ../shared/scenes, loaded through our JSON scene files in scenes/
// (cameras, paths, sky), have the triangle counts and bounding boxes of their README. Each test
// loads its scene once (ctest runs every test in its own process).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>

#include "scene/load.h"
#include "scene/stats.h"

namespace tuneray {
namespace {

struct SharedScene {
  const char* json;  // in scenes/
  const char* file;
  size_t triangles;
  Vec3f lo, hi;
  size_t textures;
};

std::string shared_path(const char* file) {
  return std::string(TUNERAY_SHARED_DIR) + "/scenes/" + file;
}

class SharedScenes : public ::testing::TestWithParam<SharedScene> {};

TEST_P(SharedScenes, LoadWithReadmeCountsAndBounds) {
  const SharedScene& expected = GetParam();
  const std::string path = shared_path(expected.file);
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared scene absent: " << path;

  LoadOptions options;
  options.scenes_dir = std::string(TUNERAY_SHARED_DIR) + "/scenes";
  const std::string json = std::string(TUNERAY_SOURCE_DIR) + "/scenes/" + expected.json;
  auto start = std::chrono::steady_clock::now();
  Scene s = load_scene(json, options);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[ info ] " << expected.file << ": " << s.triangles.size() << " triangles, "
            << s.positions.size() << " vertices, " << s.memory_bytes() / (1 << 20) << " MiB, "
            << seconds << " s\n";

  EXPECT_EQ(s.triangles.size(), expected.triangles);
  BBox b = s.bounds();
  const float tol = 1e-3f * length(expected.hi - expected.lo);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b.lo[k], expected.lo[k], tol) << "axis " << k;
    EXPECT_NEAR(b.hi[k], expected.hi[k], tol) << "axis " << k;
  }
  EXPECT_EQ(s.textures.size(), expected.textures);
  ASSERT_EQ(s.normals.size(), s.positions.size());
  for (Vec3f n : s.normals) ASSERT_NEAR(length(n), 1.0f, 1e-4f);
  for (uint32_t id : s.material_ids) ASSERT_LT(id, s.materials.size());
  ASSERT_FALSE(s.cameras.empty());
  EXPECT_NE(s.cameras[0].name, "auto");  // the JSON's own camera
  ASSERT_FALSE(s.camera_paths.empty());
  EXPECT_GE(s.camera_paths[0].keyframes.size(), 4u);
  EXPECT_GT(compute_stats(s).lights, 0u);
  for (const std::string& note : s.notes) {  // the JSON lights and frames the scene itself
    EXPECT_EQ(note.find("automatic"), std::string::npos) << note;
    EXPECT_EQ(note.find("no lights"), std::string::npos) << note;
  }
}

INSTANTIATE_TEST_SUITE_P(Readme, SharedScenes,
                         ::testing::Values(SharedScene{"cornell-box-original.json",
                                                       "cornell-box/CornellBox-Original.obj",
                                                       36,
                                                       {-1.02f, 0, -1.04f},
                                                       {1, 1.99f, 0.99f},
                                                       0},
                                           SharedScene{"cornell-box-water.json",
                                                       "cornell-box/CornellBox-Water.obj",
                                                       7088,
                                                       {-1.02f, 0, -1.04f},
                                                       {1.0041f, 1.59f, 0.99f},
                                                       0},
                                           SharedScene{"teapot.json",
                                                       "teapot/teapot.obj",
                                                       15704,
                                                       {-71.8925f, 0, -47.9284f},
                                                       {82.294f, 79.0066f, 47.9284f},
                                                       1},
                                           SharedScene{"stanford-bunny.json",
                                                       "stanford-bunny/bunny.obj",
                                                       144046,
                                                       {-0.9559f, 0.021f, -0.543f},
                                                       {0.6579f, 1.6418f, 0.6895f},
                                                       0},
                                           SharedScene{"conference.json",
                                                       "conference/conference.obj",
                                                       331179,
                                                       {-1020.13f, -2.7924f, -1055.66f},
                                                       {1685.81f, 650.293f, 668.489f},
                                                       0},
                                           SharedScene{"lost-empire.json",
                                                       "lost-empire/lost_empire.obj",
                                                       224998,
                                                       {-37, 0, -82},
                                                       {38, 49, 83},
                                                       2},
                                           SharedScene{"bmw-m6.json",
                                                       "bmw-m6/bmw-m6.obj",
                                                       792746,
                                                       {-23.9736f, -1.43298f, -28.2915f},
                                                       {25.8807f, 13.4351f, 26.5841f},
                                                       0},
                                           SharedScene{"sports-car.json",
                                                       "sports-car/sportsCar.obj",
                                                       300603,
                                                       {-1.1401f, -0.0036f, -2.3312f},
                                                       {1.1401f, 1.0875f, 2.236f},
                                                       0}),
                         [](const auto& info) {
                           std::string name =
                               std::filesystem::path(info.param.file).stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace tuneray
