// Frame measurement: rebuild policy per objective, the kept trees, and refused builds.
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

BvhConfig with_branching_and_leaf(int branching, int max_leaf) {
  BvhConfig c;
  c.branching = branching;
  c.max_leaf = max_leaf;
  return c;
}

void expect_same_film(const Film& a, const Film& b) {
  const Image x = a.resolve(), y = b.resolve();
  ASSERT_EQ(x.width(), y.width());
  ASSERT_EQ(x.height(), y.height());
  for (int j = 0; j < x.height(); ++j)
    for (int i = 0; i < x.width(); ++i)
      ASSERT_EQ(x.at(i, j), y.at(i, j)) << "pixel " << i << "," << j;
}

// A comparison's rounds: one frame of each candidate in turn. Each tree is built once.
TEST(FrameBench, AlternatingConfigurationsBuildEachTreeOnce) {
  Scene scene = load_scene("cornell");
  FrameBench bench(scene, tiny(), 1, Objective::kRender);
  const BvhConfig configs[3] = {BvhConfig{}, with_branching_and_leaf(4, 4),
                                with_branching_and_leaf(8, 2)};
  for (int round = 0; round < 4; ++round)
    for (int k = 0; k < 3; ++k) {
      const BvhConfig& config = configs[(k + round) % 3];
      const FrameCost c = bench.run(config, scene.cameras[0]);
      EXPECT_TRUE(c.ok);
      EXPECT_EQ(c.rebuilt, round == 0) << "round " << round << ", " << config.to_string();
      if (!c.rebuilt) {
        EXPECT_EQ(c.build_ms, 0.0);
      }
      // The frame is rendered with the tree asked for, and its statistics are that tree's.
      EXPECT_EQ(bench.accel().describe(), config.to_string());
      EXPECT_EQ(bench.build_stats().node_count,
                static_cast<const TunedBvhAccel&>(bench.accel()).tree_stats().node_count);
    }
}

// A tree taken back from the cache is the very tree that was built: the frame it renders is the
// frame a fresh build renders, bit for bit.
TEST(FrameBench, AKeptTreeRendersTheSameFilmAsAFreshBuild) {
  Scene scene = load_scene("cornell");
  const BvhConfig wide = with_branching_and_leaf(8, 2), narrow = with_branching_and_leaf(2, 8);
  FrameBench cached(scene, tiny(), 2, Objective::kRender);
  FrameBench fresh(scene, tiny(), 2, Objective::kRender);
  // Both render frame 2 (same sample indices) with `wide`: one from the tree it built for
  // frame 0, the other from a tree built just now.
  EXPECT_TRUE(cached.run(wide, scene.cameras[0]).rebuilt);
  EXPECT_TRUE(cached.run(narrow, scene.cameras[0]).rebuilt);
  EXPECT_FALSE(cached.run(wide, scene.cameras[0]).rebuilt);
  EXPECT_TRUE(fresh.run(narrow, scene.cameras[0]).rebuilt);
  EXPECT_FALSE(fresh.run(narrow, scene.cameras[0]).rebuilt);
  EXPECT_TRUE(fresh.run(wide, scene.cameras[0]).rebuilt);
  expect_same_film(cached.film(), fresh.film());
}

TEST(FrameBench, TheLeastRecentlyUsedTreeIsReleasedFirst) {
  Scene scene = load_scene("cornell");
  FrameBench bench(scene, tiny(), 1, Objective::kRender);
  const int kept = static_cast<int>(FrameBench::kTunedTrees);
  auto config = [](int i) {
    BvhConfig c;
    c.max_depth = 20 + i;  // a different tree for each i
    return c;
  };
  for (int i = 0; i < kept; ++i) EXPECT_TRUE(bench.run(config(i), scene.cameras[0]).rebuilt);
  for (int i = 0; i < kept; ++i) EXPECT_FALSE(bench.run(config(i), scene.cameras[0]).rebuilt);
  // Touch 0 again, then one tree too many: 1, now the least recently used, makes room.
  EXPECT_FALSE(bench.run(config(0), scene.cameras[0]).rebuilt);
  EXPECT_TRUE(bench.run(config(kept), scene.cameras[0]).rebuilt);
  EXPECT_FALSE(bench.run(config(0), scene.cameras[0]).rebuilt);
  EXPECT_FALSE(bench.run(config(2), scene.cameras[0]).rebuilt);
  EXPECT_TRUE(bench.run(config(1), scene.cameras[0]).rebuilt);
}

// Real-time rendering builds a tree for every frame by definition: nothing is kept.
TEST(FrameBench, TheTotalObjectiveKeepsNoTree) {
  Scene scene = load_scene("cornell");
  FrameBench bench(scene, tiny(), 1, Objective::kTotal);
  const BvhConfig configs[2] = {BvhConfig{}, with_branching_and_leaf(4, 4)};
  for (int frame = 0; frame < 6; ++frame) {
    const FrameCost c = bench.run(configs[frame % 2], scene.cameras[0]);
    EXPECT_TRUE(c.rebuilt) << "frame " << frame;
    EXPECT_GT(c.build_ms, 0.0);
  }
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

// A refused build loses no kept tree, including the one rendered with before it.
TEST(FrameBench, ARefusedBuildKeepsTheTreesBuiltBefore) {
  Scene scene = load_scene("voxels");
  FrameBench bench(scene, tiny(), 1, Objective::kRender);
  BvhConfig refused;
  refused.max_depth = 8;
  refused.max_leaf = 1;
  const BvhConfig wide = with_branching_and_leaf(8, 4);
  EXPECT_TRUE(bench.run(BvhConfig{}, scene.cameras[0]).rebuilt);
  EXPECT_TRUE(bench.run(wide, scene.cameras[0]).rebuilt);
  EXPECT_FALSE(bench.run(refused, scene.cameras[0]).ok);
  FrameCost back = bench.run(wide, scene.cameras[0]);
  EXPECT_TRUE(back.ok);
  EXPECT_FALSE(back.rebuilt);
  EXPECT_EQ(bench.accel().describe(), wide.to_string());
  EXPECT_FALSE(bench.run(BvhConfig{}, scene.cameras[0]).rebuilt);
  EXPECT_FALSE(bench.run(refused, scene.cameras[0]).ok);  // refused again, not taken for kept
}

// The tuner measures work sizes frame by frame: switching them must not rebuild the tree (nor
// the integrator), and must not change the image, only the time.
TEST(FrameBench, WorkSizesChangeWithoutRebuildAndGiveTheSameFilm) {
  Scene scene = load_scene("cornell");
  FrameBench tiles(scene, tiny(), 2, Objective::kRender);
  FrameBench waves(scene, tiny(), 2, Objective::kRender);
  BvhConfig config;
  EXPECT_TRUE(tiles.run(config, WorkSizes{false, 8, 4096}, scene.cameras[0]).rebuilt);
  FrameCost first = waves.run(config, WorkSizes{true, 32, 4096}, scene.cameras[0]);
  EXPECT_TRUE(first.rebuilt);
  const Image expected = tiles.film().resolve();
  const Image wave = waves.film().resolve();
  ASSERT_EQ(expected.width(), wave.width());
  for (int y = 0; y < expected.height(); ++y)
    for (int x = 0; x < expected.width(); ++x)
      ASSERT_EQ(expected.at(x, y), wave.at(x, y)) << "pixel " << x << "," << y;

  for (WorkSizes w : {WorkSizes{true, 32, 7}, WorkSizes{false, 64, 4096},
                      WorkSizes{false, 16, 4096}, WorkSizes{true, 32, 65536}}) {
    FrameCost c = tiles.run(config, w, scene.cameras[0]);
    EXPECT_TRUE(c.ok) << w.to_string();
    EXPECT_FALSE(c.rebuilt) << w.to_string();
    EXPECT_EQ(c.build_ms, 0.0) << w.to_string();
    size_t samples = 0;
    for (int y = 0; y < tiny().height; ++y)
      for (int x = 0; x < tiny().width; ++x) samples += tiles.film().samples(x, y);
    EXPECT_EQ(samples, static_cast<size_t>(2 * tiny().width * tiny().height)) << w.to_string();
  }
  // The two-argument run goes back to the settings' scheduler, still without a rebuild.
  EXPECT_FALSE(tiles.run(config, scene.cameras[0]).rebuilt);
}

// The backend is a tuning choice: each frame must really be rendered by the backend asked for,
// and each backend keeps its own tree, so alternating between them (tune's baselines) never
// rebuilds a tree that did not change.
TEST(FrameBench, TheBackendSwitchSwitchesTheAcceleratorAndKeepsBothTrees) {
  Scene scene = load_scene("cornell");
  FrameBench bench(scene, tiny(), 1, Objective::kRender);
  FrameCost native = bench.run(AccelChoice::native(), scene.cameras[0]);
  EXPECT_TRUE(native.ok);
  EXPECT_TRUE(native.rebuilt);
  EXPECT_EQ(bench.accel().name(), "native");
  EXPECT_NE(bench.accel().describe().find("quality=medium"), std::string::npos);
  EXPECT_EQ(bench.build_stats().node_count, 0u);  // Embree does not tell

  BvhConfig wide;
  wide.branching = 8;
  EXPECT_TRUE(bench.run(wide, scene.cameras[0]).rebuilt);
  EXPECT_EQ(bench.accel().name(), "tuned");
  EXPECT_EQ(bench.accel().describe(), wide.to_string());
  EXPECT_GT(bench.build_stats().node_count, 0u);  // our statistics walk counts them

  FrameCost back = bench.run(AccelChoice::native(), scene.cameras[0]);
  EXPECT_FALSE(back.rebuilt);
  EXPECT_EQ(bench.accel().name(), "native");
  EXPECT_EQ(bench.build_stats().node_count, 0u);
  EXPECT_FALSE(bench.run(wide, scene.cameras[0]).rebuilt);
  EXPECT_EQ(bench.accel().name(), "tuned");

  // Another native quality is another tree.
  EXPECT_TRUE(bench.run(AccelChoice::native(BvhQuality::kHigh), scene.cameras[0]).rebuilt);
  EXPECT_NE(bench.accel().describe().find("quality=high"), std::string::npos);
  // Both backends render every sample of the frame.
  size_t samples = 0;
  for (int y = 0; y < tiny().height; ++y)
    for (int x = 0; x < tiny().width; ++x) samples += bench.film().samples(x, y);
  EXPECT_EQ(samples, static_cast<size_t>(tiny().width * tiny().height));
}

TEST(FrameBench, NativeUnderTheTotalObjectiveRebuildsEveryFrame) {
  Scene scene = load_scene("cornell");
  FrameBench bench(scene, tiny(), 1, Objective::kTotal);
  bench.run(AccelChoice::native(), scene.cameras[0]);
  FrameCost c = bench.run(AccelChoice::native(), scene.cameras[0]);
  EXPECT_TRUE(c.rebuilt);
  EXPECT_GT(c.build_ms, 0.0);
  EXPECT_DOUBLE_EQ(c.cost_ms(Objective::kTotal), c.build_ms + c.render_ms);
}

TEST(FrameBench, ARefusedTunedBuildCostsInfinityAndLeavesNativeBuilt) {
  Scene scene = load_scene("voxels");
  FrameBench bench(scene, tiny(), 1, Objective::kRender);
  EXPECT_TRUE(bench.run(AccelChoice::native(), scene.cameras[0]).ok);
  BvhConfig refused;
  refused.max_depth = 8;
  refused.max_leaf = 1;
  FrameCost c = bench.run(AccelChoice::tuned(refused), scene.cameras[0]);
  EXPECT_FALSE(c.ok);
  EXPECT_TRUE(std::isinf(c.cost_ms(Objective::kRender)));
  EXPECT_TRUE(std::isinf(c.cost_ms(Objective::kTotal)));
  FrameCost native = bench.run(AccelChoice::native(), scene.cameras[0]);
  EXPECT_TRUE(native.ok);
  EXPECT_FALSE(native.rebuilt);
  EXPECT_EQ(bench.accel().name(), "native");
}

}  // namespace
}  // namespace tuneray
