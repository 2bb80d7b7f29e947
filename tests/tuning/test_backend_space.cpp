// The backend as a tuner parameter: native Embree and its build quality in front of the BVH
// parameters, which are pinned to their defaults under native (so every native point is one of
// three configurations), the mappings to AccelChoice and back, and the BVH-only space left as
// databases know it.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "tuning/accel_choice.h"
#include "tuning/bvh_space.h"
#include "tuning/render_space.h"
#include "tuning_fixtures.h"

namespace tuneray {
namespace {

const char* const kBvhParams[] = {"quality",         "branching", "max_depth",  "sah_block_size",
                                  "min_leaf",        "max_leaf",  "cost_ratio", "static",
                                  "compact",         "robust",    "collapse",   "reinsert",
                                  "optimal_collapse"};

TEST(BackendSpace, BackendAndNativeQualityComeFirst) {
  tuner::Space space = make_backend_space();
  tuner::Space bvh = make_bvh_space();
  ASSERT_EQ(space.size(), bvh.size() + 5);
  EXPECT_EQ(space.param(0).name, "backend");
  EXPECT_EQ(space.param(0).labels, (std::vector<std::string>{"tuned", "native"}));
  EXPECT_EQ(space.param(1).name, "native_quality");
  EXPECT_EQ(space.param(1).labels, (std::vector<std::string>{"low", "medium", "high"}));
  for (size_t i = 0; i < bvh.size(); ++i) EXPECT_EQ(space.param(i + 2).name, bvh.param(i).name);
  EXPECT_EQ(space.param(space.size() - 3).name, "collapse");
  EXPECT_EQ(space.param(space.size() - 2).name, "reinsert");
  EXPECT_EQ(space.param(space.size() - 1).name, "optimal_collapse");
  // The default stays the study's: Embree's recommended build of our tree.
  EXPECT_EQ(to_accel_choice(space.default_config()), AccelChoice::tuned(BvhConfig{}));
  EXPECT_EQ(space.default_config().get_enum("native_quality"), "medium");
}

TEST(BackendSpace, NativePinsEveryTunedParameterToItsDefault) {
  tuner::Space space = make_backend_space();
  const tuner::Config plain = space.parse("backend=native");
  tuner::Config c = to_tuner_config(space, AccelChoice::tuned(testing::every_parameter_changed()));
  c.set_enum("backend", "native");
  c = space.canonical(c);
  EXPECT_EQ(c, plain) << c.to_string();
  const tuner::Config defaults = space.default_config();
  for (const char* name : kBvhParams)
    EXPECT_EQ(c.values()[space.index_of(name)], defaults.values()[space.index_of(name)]) << name;
  EXPECT_EQ(to_accel_choice(c), AccelChoice::native(BvhQuality::kMedium));
  EXPECT_EQ(space.parse("backend=native,branching=8,max_leaf=4,cost_ratio=4,static=true"), plain);
  // ... while the native quality is its own parameter there,
  EXPECT_NE(space.parse("backend=native,native_quality=high"), plain);
  EXPECT_EQ(to_accel_choice(space.parse("backend=native,native_quality=low")),
            AccelChoice::native(BvhQuality::kLow));
  // ... and pinned under tuned, where the BVH parameters are free again.
  EXPECT_EQ(space.parse("native_quality=high"), space.default_config());
  EXPECT_NE(space.parse("branching=8"), space.default_config());
  // Morton still ignores the SAH parameters under tuned, but not max_leaf (the leaf size of its
  // balanced subtrees near max_depth).
  EXPECT_EQ(space.parse("quality=low,sah_block_size=8,cost_ratio=4"), space.parse("quality=low"));
  EXPECT_NE(space.parse("quality=low,max_leaf=4"), space.parse("quality=low"));
  EXPECT_EQ(space.parse("backend=native,max_leaf=4"), space.parse("backend=native"));
  // Morton leaves of up to 32 (min_leaf is their size) are in the backend space; the BVH-only
  // space keeps the range its databases were measured with.
  const tuner::Space bvh = make_bvh_space();
  EXPECT_EQ(space.param(space.index_of("min_leaf")).hi, 32);
  EXPECT_EQ(bvh.param(bvh.index_of("min_leaf")).hi, 8);
  EXPECT_EQ(to_bvh_config(space.parse("quality=low,min_leaf=24")).min_leaf, 24);
}

TEST(BackendSpace, ChoicesRoundTrip) {
  tuner::Space space = make_backend_space();
  for (const AccelChoice& choice :
       {AccelChoice::tuned(BvhConfig{}), AccelChoice::tuned(testing::every_parameter_changed()),
        AccelChoice::native(BvhQuality::kLow), AccelChoice::native(BvhQuality::kMedium),
        AccelChoice::native(BvhQuality::kHigh)}) {
    const tuner::Config c = to_tuner_config(space, choice);
    EXPECT_EQ(to_accel_choice(c), choice) << choice.to_string();
    EXPECT_EQ(to_accel_choice(c).to_string(), choice.to_string());
    EXPECT_EQ(space.parse(c.to_string()), c);
    EXPECT_EQ(parse_accel_choice(choice.to_string()), choice) << choice.to_string();
  }
  EXPECT_EQ(to_bvh_config(to_tuner_config(space, testing::every_parameter_changed())).to_string(),
            testing::every_parameter_changed().to_string());
}

TEST(BackendSpace, CollapseCountsOnlyForTwoAndFourWideTrees) {
  tuner::Space space = make_backend_space();
  EXPECT_TRUE(space.default_config().get_bool("collapse"));
  EXPECT_NE(space.parse("collapse=false"), space.default_config());
  EXPECT_NE(space.parse("branching=4,collapse=false"), space.parse("branching=4"));
  EXPECT_EQ(space.parse("branching=8,collapse=false"), space.parse("branching=8"));
  EXPECT_EQ(space.parse("backend=native,collapse=false"), space.parse("backend=native"));
  BvhConfig narrow;
  narrow.branching = 4;
  narrow.collapse = false;
  EXPECT_EQ(to_bvh_config(to_tuner_config(space, narrow)), narrow);
  EXPECT_TRUE(to_bvh_config(space.default_config()).collapses());
}

TEST(BackendSpace, ReinsertCountsOnlyForBinaryTrees) {
  tuner::Space space = make_backend_space();
  EXPECT_FALSE(space.default_config().get_bool("reinsert"));
  EXPECT_NE(space.parse("reinsert=true"), space.default_config());
  EXPECT_NE(space.parse("collapse=false,reinsert=true"), space.parse("collapse=false"));
  EXPECT_EQ(space.parse("branching=4,reinsert=true"), space.parse("branching=4"));
  EXPECT_EQ(space.parse("branching=8,reinsert=true"), space.parse("branching=8"));
  EXPECT_EQ(space.parse("backend=native,reinsert=true"), space.parse("backend=native"));
  BvhConfig binary;
  binary.reinsert = true;
  EXPECT_EQ(to_bvh_config(to_tuner_config(space, binary)), binary);
  EXPECT_TRUE(to_bvh_config(space.parse("reinsert=true")).reinserts());
  // The BVH-only space has no such parameter: it means reinsert=0 and refuses reinsert=1.
  EXPECT_FALSE(to_bvh_config(make_bvh_space().default_config()).reinsert);
  binary.collapse = false;
  EXPECT_THROW(to_tuner_config(make_bvh_space(), binary), std::invalid_argument);
}

TEST(BackendSpace, OptimalCollapseCountsOnlyWhereTheTreeIsCollapsed) {
  tuner::Space space = make_backend_space();
  EXPECT_FALSE(space.default_config().get_bool("optimal_collapse"));
  EXPECT_NE(space.parse("optimal_collapse=true"), space.default_config());
  EXPECT_NE(space.parse("branching=4,optimal_collapse=true"), space.parse("branching=4"));
  EXPECT_EQ(space.parse("branching=8,optimal_collapse=true"), space.parse("branching=8"));
  EXPECT_EQ(space.parse("collapse=false,optimal_collapse=true"), space.parse("collapse=false"));
  EXPECT_EQ(space.parse("backend=native,optimal_collapse=true"), space.parse("backend=native"));
  BvhConfig planned;
  planned.optimal_collapse = true;
  EXPECT_EQ(to_bvh_config(to_tuner_config(space, planned)), planned);
  EXPECT_TRUE(to_bvh_config(space.parse("optimal_collapse=true")).collapses_optimally());
  // The BVH-only space has no such parameter: it means 0 and refuses a collapse that needs it.
  EXPECT_FALSE(to_bvh_config(make_bvh_space().default_config()).optimal_collapse);
  EXPECT_THROW(to_tuner_config(make_bvh_space(), planned), std::invalid_argument);
}

TEST(BackendSpace, SeedsAreEmbreesBvh8LeavesAndReinsertionOnlyWhereItsBuildIsFree) {
  const tuner::Space space = make_backend_space();
  const std::vector<tuner::Config> render = tuning_seeds(space, false);
  ASSERT_EQ(render.size(), 4u);
  EXPECT_EQ(to_bvh_config(render[0]), embree_bvh8_config());
  EXPECT_EQ(to_bvh_config(render[1]), embree_bvh8_config(BvhQuality::kHigh));
  const BvhConfig reinserted = to_bvh_config(render[2]);
  EXPECT_TRUE(reinserted.reinserts());
  EXPECT_TRUE(reinserted.collapses_optimally());
  EXPECT_TRUE(reinserted.is_static);
  EXPECT_EQ(reinserted.min_leaf, 4);
  EXPECT_EQ(reinserted.max_leaf, 28);
  EXPECT_EQ(reinserted.sah_block_size, 4);
  EXPECT_EQ(reinserted.quality, BvhQuality::kMedium);
  EXPECT_FLOAT_EQ(reinserted.cost_ratio(), kReinsertedSeedCostRatio);
  EXPECT_NE(kReinsertedSeedCostRatio, embree_bvh8_config().cost_ratio());
  // The same reinserted tree from the spatial-split build, at Embree's pricing.
  BvhConfig split = to_bvh_config(render[3]);
  EXPECT_EQ(split.quality, BvhQuality::kHigh);
  EXPECT_FLOAT_EQ(split.cost_ratio(), embree_bvh8_config().cost_ratio());
  split.quality = BvhQuality::kMedium;
  split.set_cost_ratio(kReinsertedSeedCostRatio);
  EXPECT_EQ(split, reinserted);
  const std::vector<tuner::Config> total = tuning_seeds(space, true);
  ASSERT_EQ(total.size(), 1u);
  EXPECT_EQ(to_bvh_config(total[0]), embree_bvh8_config());
  // The BVH-only space has no reinsertion to seed.
  EXPECT_EQ(tuning_seeds(make_bvh_space(), false).size(), 2u);
}

TEST(BackendSpace, TheBvhOnlySpaceHasNoNativeChoice) {
  tuner::Space bvh = make_bvh_space();
  EXPECT_EQ(to_accel_choice(bvh.default_config()),
            AccelChoice::tuned(testing::bvh_only_defaults()));
  EXPECT_THROW(to_tuner_config(bvh, BvhConfig{}), std::invalid_argument);
  EXPECT_EQ(
      to_accel_choice(to_tuner_config(bvh, AccelChoice::tuned(testing::every_parameter_changed())))
          .bvh,
      testing::every_parameter_changed());
  EXPECT_THROW(to_tuner_config(bvh, AccelChoice::native()), std::invalid_argument);
}

// Databases written before the backend existed hold the BVH-only space's description; it must
// not change (the database refuses a key with another description).
TEST(BackendSpace, BvhOnlyDescriptionIsTheOneDatabasesHold) {
  tuner::Space legacy;
  legacy.add_enum("quality", {"low", "medium", "high"}, "medium")
      .add_int_set("branching", {2, 4, 8}, 2)
      .add_int("max_depth", 8, 64, 32)
      .add_int_set("sah_block_size", {1, 2, 4, 8, 16}, 1)
      .add_int("min_leaf", 1, 8, 1)
      .add_int("max_leaf", 1, 32, 32)
      .add_real("cost_ratio", 1.0 / 20.0, 20.0, 1.0, tuner::Scale::kLog)
      .add_bool("static", false)
      .add_bool("compact", false)
      .add_bool("robust", false);
  for (const char* name : {"sah_block_size", "max_leaf", "cost_ratio"})
    legacy.add_condition(name, tuner::Space::when_enum_not("quality", {"low"}));
  EXPECT_EQ(make_bvh_space().describe(), legacy.describe());
  EXPECT_NE(make_backend_space().describe(), legacy.describe());
}

// The search's first simplex spans both backends, and every native point decodes to one of the
// three native configurations.
TEST(BackendSpace, DecodedPointsCoverBothBackendsAndNativeCollapses) {
  tuner::Space space = make_backend_space();
  std::set<std::string> native_configs;
  int tuned = 0;
  for (int i = 0; i < 300; ++i) {
    std::vector<double> point(space.size());
    for (size_t d = 0; d < point.size(); ++d) point[d] = std::fmod(0.37 * (i + 1) * (d + 3), 1.0);
    tuner::Config c = space.feasible(point);
    AccelChoice choice = to_accel_choice(c);
    EXPECT_EQ(choice.bvh.validate(), "") << c.to_string();
    if (choice.is_native())
      native_configs.insert(c.to_string());
    else
      ++tuned;
  }
  EXPECT_GT(tuned, 50);
  EXPECT_EQ(native_configs.size(), 3u);
}

TEST(BackendSpace, WorkSizesExtendIt) {
  RenderSettings settings;
  tuner::Space space = make_render_space(settings, make_backend_space());
  EXPECT_EQ(space.size(), make_backend_space().size() + 3);
  const WorkSizes work{false, 16, settings.quality.batch_size};
  tuner::Config c = to_tuner_config(space, AccelChoice::native(BvhQuality::kHigh), work);
  EXPECT_EQ(to_accel_choice(c), AccelChoice::native(BvhQuality::kHigh));
  EXPECT_EQ(to_work_sizes(c), work);
  EXPECT_THROW(to_tuner_config(make_render_space(settings), AccelChoice::native(), work),
               std::invalid_argument);
}

TEST(AccelChoice, TextNamesTheBackendAndParsesBack) {
  EXPECT_EQ(AccelChoice::native().to_string(), "backend=native,quality=medium");
  EXPECT_EQ(AccelChoice::tuned(BvhConfig{}).to_string(),
            "backend=tuned," + BvhConfig{}.to_string());
  EXPECT_EQ(parse_accel_choice("branching=8"), AccelChoice::tuned(parse_bvh_config("branching=8")));
  EXPECT_EQ(parse_accel_choice("backend=native,quality=high"),
            AccelChoice::native(BvhQuality::kHigh));
  EXPECT_THROW(parse_accel_choice("backend=octree"), std::invalid_argument);
  EXPECT_THROW(parse_accel_choice("backend=native,branching=8"), std::invalid_argument);
  EXPECT_THROW(parse_accel_choice("backend=native,quality=ultra"), std::invalid_argument);
  // The same tree is the same choice, whatever the other backend's fields hold.
  AccelChoice a = AccelChoice::native(), b = AccelChoice::native();
  b.bvh.branching = 8;
  EXPECT_EQ(a, b);
  EXPECT_NE(AccelChoice::native(BvhQuality::kHigh), a);
  EXPECT_NE(AccelChoice::tuned(BvhConfig{}), a);
  EXPECT_EQ(AccelChoice::native(BvhQuality::kHigh).native_options().quality,
            RTC_BUILD_QUALITY_HIGH);
  EXPECT_EQ(AccelChoice::native().native_options().quality, NativeOptions{}.quality);
}

}  // namespace
}  // namespace tuneray
