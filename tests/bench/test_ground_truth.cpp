// The ground-truth cache: one file per key, progress reported per pass, read back unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "bench/ground_truth.h"
#include "common/scene_with_accel.h"
#include "common/temp_dir.h"
#include "image/io.h"
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
  testing::SceneWithNativeAccel built(load_scene("cornell"));
  const Scene& scene = built.scene;
  const Accel& accel = built.accel;
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

// The halves are written beside the truth, are its even and odd samples (their mean is the
// truth), and a cache written without them is rendered again only when they are asked for.
TEST(GroundTruth, KeepsItsHalvesAndRendersAgainWhenTheyAreAskedForAndMissing) {
  testing::TempDir dir;
  testing::SceneWithNativeAccel built(load_scene("cornell"));
  const Scene& scene = built.scene;
  const Accel& accel = built.accel;
  GroundTruthKey key{"cornell", scene.cameras[0], 16, 12, 3, 40, 0};
  const std::string d = dir.file("t");
  Image truth = ground_truth(d, key, scene, accel);
  std::optional<GroundTruthHalves> halves = ground_truth_halves(d, key);
  ASSERT_TRUE(halves);
  double largest_gap = 0, largest_difference = 0;
  for (int y = 0; y < key.height; ++y)
    for (int x = 0; x < key.width; ++x) {
      const Color mean = (halves->a.at(x, y) + halves->b.at(x, y)) * 0.5f;
      const Color gap = mean - truth.at(x, y);
      const Color difference = halves->a.at(x, y) - halves->b.at(x, y);
      largest_gap = std::max(
          {largest_gap, std::abs(double{gap.x}), std::abs(double{gap.y}), std::abs(double{gap.z})});
      largest_difference = std::max(largest_difference, double{std::abs(difference.x)});
    }
  EXPECT_LT(largest_gap, 1e-5);         // 20 samples each: the mean of the halves is the truth
  EXPECT_GT(largest_difference, 0.01);  // and they are not the same samples

  // An older cache: the truth alone.
  for (int half : {0, 1}) std::filesystem::remove(ground_truth_half_path(d, key, half));
  EXPECT_FALSE(ground_truth_halves(d, key));
  GroundTruthInfo info;
  ground_truth(d, key, scene, accel, &info);
  EXPECT_FALSE(info.rendered);  // not asked for: the cached truth serves
  key.require_halves = true;
  EXPECT_EQ(ground_truth_path(d, key),
            ground_truth_path(d, GroundTruthKey{key.scene_spec, key.camera, 16, 12, 3, 40, 0}));
  Image again = ground_truth(d, key, scene, accel, &info);
  EXPECT_TRUE(info.rendered);
  EXPECT_EQ(compare_images(again, truth).rmse, 0.0);  // same seed, same samples
  EXPECT_TRUE(ground_truth_halves(d, key));

  // A half of another size is refused by name.
  write_image(ground_truth_half_path(d, key, 1), Image(3, 2));
  try {
    ground_truth_halves(d, key);
    FAIL() << "a 3x2 half was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(".half1.exr"), std::string::npos) << e.what();
  }
}

TEST(GroundTruth, StopsAtTheErrorTargetWithEstimates) {
  testing::TempDir dir;
  testing::SceneWithNativeAccel built(load_scene("furnace"));
  const Scene& scene = built.scene;
  const Accel& accel = built.accel;
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
