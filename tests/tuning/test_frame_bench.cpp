// Frame measurement: rebuild policy per objective and refused builds.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/load.h"
#include "tuning/frame_bench.h"

namespace tuneray {
namespace {

RenderSettings tiny() {
  RenderSettings s;
  s.width = 16;
  s.height = 12;
  return s;
}

TEST(FrameBench, RenderObjectiveRebuildsOnlyWhenTheConfigurationChanges) {
  Scene scene = load_scene("cornell");
  FrameBench bench(scene, tiny(), 1, Objective::kRender);
  BvhConfig a, b;
  b.branching = 4;
  EXPECT_TRUE(bench.run(a, scene.cameras[0]).rebuilt);
  FrameCost again = bench.run(a, scene.cameras[0]);
  EXPECT_FALSE(again.rebuilt);
  EXPECT_EQ(again.build_ms, 0.0);
  EXPECT_EQ(again.cost_ms(Objective::kRender), again.render_ms);
  EXPECT_TRUE(bench.run(b, scene.cameras[0]).rebuilt);
}

TEST(FrameBench, TotalObjectiveRebuildsEveryFrameAndCountsIt) {
  Scene scene = load_scene("cornell");
  FrameBench bench(scene, tiny(), 1, Objective::kTotal);
  BvhConfig a;
  bench.run(a, scene.cameras[0]);
  FrameCost c = bench.run(a, scene.cameras[0]);
  EXPECT_TRUE(c.rebuilt);
  EXPECT_GT(c.build_ms, 0.0);
  EXPECT_DOUBLE_EQ(c.cost_ms(Objective::kTotal), c.build_ms + c.render_ms);
}

TEST(FrameBench, ARefusedBuildIsAnInfinitelySlowFrameNotACrash) {
  Scene scene = load_scene("voxels");
  FrameBench bench(scene, tiny(), 1, Objective::kRender);
  BvhConfig deep_enough_to_fail;
  deep_enough_to_fail.max_depth = 8;  // far too shallow for tens of thousands of triangles
  deep_enough_to_fail.max_leaf = 1;
  FrameCost c = bench.run(deep_enough_to_fail, scene.cameras[0]);
  EXPECT_FALSE(c.ok);
  EXPECT_FALSE(c.error.empty());
  EXPECT_TRUE(std::isinf(c.cost_ms(Objective::kRender)));
  EXPECT_TRUE(bench.run(BvhConfig{}, scene.cameras[0]).ok);  // and the next build works
}

}  // namespace
}  // namespace tuneray
