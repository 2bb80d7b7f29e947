// The BVH search space: mapping to BvhConfig and back, conditions and the constraint.
#include <gtest/gtest.h>

#include <cmath>

#include "tuning/bvh_space.h"
#include "tuning/tuner_state.h"
#include "tuning_fixtures.h"

namespace tuneray {
namespace {

TEST(BvhSpace, DefaultsAreEmbreesRecommendedOnes) {
  tuner::Space space = make_bvh_space();
  EXPECT_EQ(space.size(), 10u);  // 11 parameters, the two costs folded into one ratio
  EXPECT_EQ(to_bvh_config(space.default_config()), testing::bvh_only_defaults());
}

TEST(BvhSpace, RoundTripsEveryParameter) {
  tuner::Space space = make_bvh_space();
  const BvhConfig b = testing::every_parameter_changed();
  BvhConfig back = to_bvh_config(to_tuner_config(space, b));
  EXPECT_EQ(back.to_string(), b.to_string());
}

TEST(BvhSpace, MortonIgnoresSahParametersSoTheyCollapse) {
  tuner::Space space = make_bvh_space();
  BvhConfig a = testing::bvh_only_defaults(), b = a;
  a.quality = b.quality = BvhQuality::kLow;
  a.sah_block_size = 8;
  a.set_cost_ratio(10.0f);
  EXPECT_EQ(to_tuner_config(space, a), to_tuner_config(space, b));
  a.quality = b.quality = BvhQuality::kMedium;
  EXPECT_NE(to_tuner_config(space, a), to_tuner_config(space, b));
}

// max_leaf sizes the balanced subtrees Morton builds near max_depth: it stays a free parameter.
TEST(BvhSpace, MortonKeepsMaxLeaf) {
  tuner::Space space = make_bvh_space();
  BvhConfig a = testing::bvh_only_defaults(), b = a;
  a.quality = b.quality = BvhQuality::kLow;
  a.max_leaf = 4;
  EXPECT_NE(to_tuner_config(space, a), to_tuner_config(space, b));
  EXPECT_EQ(to_bvh_config(to_tuner_config(space, a)).max_leaf, 4);
}

TEST(BvhSpace, EveryDecodedPointIsAValidBvhConfig) {
  tuner::Space space = make_bvh_space();
  for (int i = 0; i < 200; ++i) {
    std::vector<double> point(space.size());
    for (size_t d = 0; d < point.size(); ++d) point[d] = std::fmod(0.37 * (i + 1) * (d + 3), 1.0);
    tuner::Config c = space.feasible(point);
    BvhConfig b = to_bvh_config(c);
    EXPECT_LE(b.min_leaf, b.max_leaf) << c.to_string();
    EXPECT_EQ(b.validate(), "") << c.to_string();
  }
}

TEST(TunerState, SchemaHasSeventeenIndicatorsInRange) {
  tuner::IndicatorSchema schema = make_indicator_schema();
  EXPECT_EQ(schema.size(), 17u);
}

}  // namespace
}  // namespace tuneray
