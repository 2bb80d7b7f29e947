#include "tuner/nearest_neighbour.h"

#include <gtest/gtest.h>

#include "tuner/space.h"

namespace tuneray::tuner {
namespace {

class NearestNeighbourTest : public ::testing::Test {
 protected:
  NearestNeighbourTest() { space_.add_int("block", 1, 64, 8); }
  Config block(int64_t b) { return space_.default_config().set_int("block", b); }
  Space space_;
};

TEST_F(NearestNeighbourTest, ExactStateGivesItsBest) {
  NearestNeighbourPredictor nn;
  nn.set_best(1, std::vector<double>{0.1, 0.1}, block(4));
  nn.set_best(2, std::vector<double>{0.9, 0.2}, block(32));
  const auto p = nn.predict(std::vector<double>{0.9, 0.2});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->config, block(32));
  EXPECT_EQ(p->state_id, 2);
  EXPECT_EQ(p->distance, 0.0);
  EXPECT_TRUE(p->known);
}

TEST_F(NearestNeighbourTest, UnknownStateGivesNearestBestAndReplacingABestWorks) {
  NearestNeighbourPredictor nn;
  nn.set_best(1, std::vector<double>{0.0, 0.0}, block(4));
  nn.set_best(2, std::vector<double>{1.0, 1.0}, block(32));
  EXPECT_EQ(nn.predict(std::vector<double>{0.4, 0.4})->config, block(4));
  EXPECT_EQ(nn.predict(std::vector<double>{0.6, 0.6})->config, block(32));
  nn.set_best(1, std::vector<double>{0.0, 0.0}, block(2));
  EXPECT_EQ(nn.predict(std::vector<double>{0.4, 0.4})->config, block(2));
  EXPECT_EQ(nn.size(), 2u);
  EXPECT_NEAR(nn.predict(std::vector<double>{0.3, 0.4})->distance, 0.5, 1e-12);
}

TEST_F(NearestNeighbourTest, ThresholdMarksFarStatesUnknown) {
  NearestNeighbourPredictor nn(0.2);
  EXPECT_FALSE(nn.predict(std::vector<double>{0.5}));
  nn.set_best(1, std::vector<double>{0.0}, block(4));
  EXPECT_TRUE(nn.predict(std::vector<double>{0.15})->known);
  const auto far = nn.predict(std::vector<double>{0.5});
  ASSERT_TRUE(far);
  EXPECT_FALSE(far->known);
  EXPECT_EQ(far->config, block(4));  // still offered as a warm start
}

}  // namespace
}  // namespace tuneray::tuner
