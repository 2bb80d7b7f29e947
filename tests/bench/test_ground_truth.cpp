// The ground-truth cache: one file per key, progress reported per pass, read back unchanged.
#include <gtest/gtest.h>

#include "accel/embree_native.h"
#include "bench/ground_truth.h"
#include "common/temp_dir.h"
#include "image/metrics.h"
#include "scene/load.h"

namespace tuneray {
namespace {

TEST(GroundTruth, PathCoversEveryFieldOfTheKey) {
  Scene scene = load_scene("cornell");
  GroundTruthKey key{"cornell", scene.cameras[0], 16, 12, 3, 64, 0};
  const std::string path = ground_truth_path("d", key);
  EXPECT_EQ(path, ground_truth_path("d", key));
  EXPECT_EQ(path.substr(0, 8), "d/truth-");
  std::vector<GroundTruthKey> others(6, key);
  others[0].scene_spec = "furnace";
  others[1].camera.position.x += 1;
  others[2].width = 17;
  others[3].max_bounces = 4;
  others[4].spp = 65;
  others[5].until_rmse = 0.01;
  for (const GroundTruthKey& other : others) EXPECT_NE(ground_truth_path("d", other), path);
}

TEST(GroundTruth, RendersInPassesThenReadsTheCache) {
  testing::TempDir dir;
  Scene scene = load_scene("cornell");
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  GroundTruthKey key{"cornell", scene.cameras[0], 16, 12, 3, 40, 0};
  std::vector<int> passes;
  GroundTruthInfo info;
  Image first =
      ground_truth(dir.file("t"), key, scene, accel, &info, [&](int spp, double estimate) {
        passes.push_back(spp);
        EXPECT_LT(estimate, 0);
      });
  EXPECT_EQ(passes, (std::vector<int>{16, 16, 8}));
  EXPECT_TRUE(info.rendered);
  EXPECT_EQ(info.spp, 40);
  passes.clear();
  Image again = ground_truth(dir.file("t"), key, scene, accel, &info,
                             [&](int spp, double) { passes.push_back(spp); });
  EXPECT_TRUE(passes.empty());
  EXPECT_FALSE(info.rendered);
  EXPECT_EQ(info.spp, 0);
  EXPECT_EQ(compare_images(first, again).rmse, 0.0);
}

TEST(GroundTruth, StopsAtTheErrorTargetWithEstimates) {
  testing::TempDir dir;
  Scene scene = load_scene("furnace");
  EmbreeNativeAccel accel;
  accel.build({scene.positions.data(), scene.positions.size(), scene.triangles.data(),
               scene.triangles.size()});
  GroundTruthKey key{"furnace", scene.cameras[0], 8, 6, 3, 1 << 16, 1e30};
  std::vector<double> estimates;
  GroundTruthInfo info;
  ground_truth(dir.file("t"), key, scene, accel, &info,
               [&](int, double estimate) { estimates.push_back(estimate); });
  ASSERT_EQ(estimates.size(), 1u) << "any estimate is below 1e30: one pass";
  EXPECT_GE(estimates[0], 0);
  EXPECT_EQ(info.spp, 16);
}

}  // namespace
}  // namespace tuneray
