// The BVH space extended with scheduler and work sizes: shape, conditions (the size a scheduler
// ignores is pinned) and the mapping to (BvhConfig, WorkSizes) and back.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "tuning/bvh_space.h"
#include "tuning/render_space.h"
#include "tuning_fixtures.h"

namespace tuneray {
namespace {

// The wave size the renderer uses unless told otherwise (docs/quality.md's sweep chose it).
const int kDefaultBatch = RenderSettings{}.quality.batch_size;

TEST(RenderSpace, IsTheBvhSpacePlusSchedulerAndTwoSizes) {
  tuner::Space bvh = make_bvh_space();
  tuner::Space space = make_render_space(RenderSettings{});
  ASSERT_EQ(space.size(), bvh.size() + 3);
  for (size_t i = 0; i < bvh.size(); ++i) EXPECT_EQ(space.param(i).name, bvh.param(i).name);
  EXPECT_EQ(space.param(bvh.size()).name, "scheduler");
  EXPECT_EQ(space.param(bvh.size()).labels, (std::vector<std::string>{"tile", "wavefront"}));
  EXPECT_EQ(space.param(bvh.size() + 1).name, "tile_size");
  EXPECT_EQ(space.param(bvh.size() + 1).int_values, (std::vector<int64_t>{8, 16, 32, 64}));
  EXPECT_EQ(space.param(bvh.size() + 2).name, "batch_size");
  EXPECT_EQ(space.param(bvh.size() + 2).int_values,
            (std::vector<int64_t>{256, 1024, 4096, 16384, 65536}));
  // The database keys samples by the space description too: the BVH-only one is unchanged.
  EXPECT_EQ(make_bvh_space().describe(), bvh.describe());
  EXPECT_NE(space.describe(), bvh.describe());
}

TEST(RenderSpace, DefaultsFollowTheRenderSettings) {
  RenderSettings tiles;
  tiles.quality.wavefront = false;
  tuner::Space space = make_render_space(tiles);
  EXPECT_EQ(to_bvh_config(space.default_config()), testing::bvh_only_defaults());
  EXPECT_EQ(to_work_sizes(space.default_config()), WorkSizes::of(tiles));
  EXPECT_EQ(space.default_config().get_enum("scheduler"), "tile");

  RenderSettings wave;
  wave.quality.wavefront = true;
  tuner::Config c = make_render_space(wave).default_config();
  EXPECT_EQ(c.get_enum("scheduler"), "wavefront");
  EXPECT_EQ(c.get_int("tile_size"), 32);
  EXPECT_EQ(c.get_int("batch_size"), kDefaultBatch);

  RenderSettings sized;  // sizes from the settings when they are in their sets
  sized.tile_size = 16;
  sized.quality.batch_size = 256;
  c = make_render_space(sized).default_config();
  EXPECT_EQ(c.get_int("tile_size"), 16);
  EXPECT_EQ(c.get_int("batch_size"), 256);
  sized.tile_size = 7;  // outside {8, 16, 32, 64}: the renderer's default
  EXPECT_EQ(make_render_space(sized).default_config().get_int("tile_size"), 32);
}

TEST(RenderSpace, TheSizeTheSchedulerIgnoresIsPinned) {
  tuner::Space space = make_render_space(RenderSettings{});
  EXPECT_EQ(space.parse("scheduler=wavefront,tile_size=8"), space.parse("scheduler=wavefront"));
  EXPECT_EQ(space.parse("scheduler=wavefront,tile_size=8").get_int("tile_size"), 32);
  EXPECT_NE(space.parse("scheduler=wavefront,batch_size=256"), space.parse("scheduler=wavefront"));
  EXPECT_EQ(space.parse("scheduler=tile,batch_size=256"), space.parse("scheduler=tile"));
  EXPECT_EQ(space.parse("scheduler=tile,batch_size=256").get_int("batch_size"), kDefaultBatch);
  EXPECT_NE(space.parse("scheduler=tile,tile_size=8"), space.parse("scheduler=tile"));
}

// Points that differ only in the ignored size decode to one configuration, so the search reuses
// its sample instead of measuring it again; the active size still takes all its values.
TEST(RenderSpace, DecodingCollapsesTheIgnoredSize) {
  tuner::Space space = make_render_space(RenderSettings{});
  const size_t scheduler = space.index_of("scheduler");
  const size_t tile = space.index_of("tile_size");
  const size_t batch = space.index_of("batch_size");
  std::vector<double> point = space.encode(space.default_config());
  for (double s : {0.25, 0.75}) {
    point[scheduler] = s;
    std::set<int64_t> tiles, batches;
    for (double u = 0.05; u < 1.0; u += 0.1) {
      point[tile] = u;
      point[batch] = 1.0 - u;
      tuner::Config c = space.decode(point);
      tiles.insert(c.get_int("tile_size"));
      batches.insert(c.get_int("batch_size"));
    }
    if (s < 0.5) {
      EXPECT_EQ(tiles.size(), 4u);
      EXPECT_EQ(batches, std::set<int64_t>{kDefaultBatch});
    } else {
      EXPECT_EQ(tiles, std::set<int64_t>{32});
      EXPECT_EQ(batches.size(), 5u);
    }
  }
}

TEST(RenderSpace, RoundTripsBvhAndWorkSizes) {
  tuner::Space space = make_render_space(RenderSettings{});
  BvhConfig b;
  b.quality = BvhQuality::kHigh;
  b.branching = 8;
  b.max_leaf = 12;
  b.set_cost_ratio(4.0f);
  b.compact = true;
  for (int t : {8, 16, 32, 64}) {
    WorkSizes w{false, t, kDefaultBatch};
    tuner::Config c = to_tuner_config(space, b, w);
    EXPECT_EQ(to_bvh_config(c).to_string(), b.to_string());
    EXPECT_EQ(to_work_sizes(c), w);
  }
  for (int n : {256, 1024, 4096, 16384, 65536}) {
    WorkSizes w{true, 32, n};
    tuner::Config c = to_tuner_config(space, b, w);
    EXPECT_EQ(to_bvh_config(c).to_string(), b.to_string());
    EXPECT_EQ(to_work_sizes(c), w);
  }
  // The ignored size may hold anything (even outside its set) and comes back as its default.
  WorkSizes odd{true, 48, 16384};
  EXPECT_EQ(to_work_sizes(to_tuner_config(space, b, odd)), (WorkSizes{true, 32, 16384}));
  EXPECT_THROW((to_tuner_config(space, b, WorkSizes{false, 48, 4096})), std::invalid_argument);
}

TEST(RenderSpace, EveryDecodedPointIsValid) {
  tuner::Space space = make_render_space(RenderSettings{});
  for (int i = 0; i < 200; ++i) {
    std::vector<double> point(space.size());
    for (size_t d = 0; d < point.size(); ++d) point[d] = std::fmod(0.37 * (i + 1) * (d + 3), 1.0);
    tuner::Config c = space.feasible(point);
    EXPECT_EQ(to_bvh_config(c).validate(), "") << c.to_string();
    WorkSizes w = to_work_sizes(c);
    EXPECT_EQ(space.parse(c.to_string()), c);
    EXPECT_EQ(w.wavefront ? w.tile_size : w.batch_size, w.wavefront ? 32 : kDefaultBatch)
        << c.to_string();
  }
}

TEST(WorkSizes, TextNamesOnlyTheActiveSize) {
  EXPECT_EQ((WorkSizes{false, 16, 1024}).to_string(), "scheduler=tile,tile_size=16");
  EXPECT_EQ((WorkSizes{true, 16, 1024}).to_string(), "scheduler=wavefront,batch_size=1024");
}

}  // namespace
}  // namespace tuneray
