// The distribution-free interval of a median: binomial ranks against their exact values, and
// the interval of a sample.
#include "tuning/median_interval.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace tuneray {
namespace {

TEST(MedianIntervalRanks, MatchTheBinomialTables) {
  // n = 10: P(B <= 1) = 11/1024 <= 0.025 < P(B <= 2) = 56/1024, so ranks 2 and 9.
  const auto ten = median_interval_ranks(10);
  ASSERT_TRUE(ten.has_value());
  EXPECT_EQ(ten->low, 2);
  EXPECT_EQ(ten->high, 9);
  EXPECT_NEAR(ten->confidence, 1 - 2 * 11.0 / 1024, 1e-12);
  // n = 30: P(B <= 9) = 22964087 / 2^30 = 0.0214 <= 0.025 < P(B <= 10) = 0.0494.
  const auto thirty = median_interval_ranks(30);
  ASSERT_TRUE(thirty.has_value());
  EXPECT_EQ(thirty->low, 10);
  EXPECT_EQ(thirty->high, 21);
  EXPECT_NEAR(thirty->confidence, 1 - 2 * 22964087.0 / 1073741824.0, 1e-12);
  // 6 values are the fewest whose range covers the median at 95 % (1 - 2/64).
  const auto six = median_interval_ranks(6);
  ASSERT_TRUE(six.has_value());
  EXPECT_EQ(six->low, 1);
  EXPECT_EQ(six->high, 6);
  EXPECT_NEAR(six->confidence, 1 - 2.0 / 64, 1e-12);
  EXPECT_FALSE(median_interval_ranks(5).has_value());
  EXPECT_FALSE(median_interval_ranks(1).has_value());
  // A lower level narrows the interval: at 90 % for n = 10, P(B <= 2) = 0.0547 <= 0.05 fails,
  // P(B <= 1) passes: still 2 and 9; at 80 %, P(B <= 2) <= 0.1: 3 and 8.
  EXPECT_EQ(median_interval_ranks(10, 0.90)->low, 2);
  EXPECT_EQ(median_interval_ranks(10, 0.80)->low, 3);
  EXPECT_THROW(median_interval_ranks(0), std::invalid_argument);
  EXPECT_THROW(median_interval_ranks(10, 1.0), std::invalid_argument);
}

TEST(MedianIntervalRanks, LargeSamplesDoNotUnderflow) {
  // Beyond 1074 values 2^-n underflows a double. Exact sums of binomial coefficients give
  // P(B <= 1937) <= 0.025 < P(B <= 1938) for n = 4000 (the normal approximation:
  // n/2 - 1.96 sqrt(n)/2 = 1938.0).
  const auto ranks = median_interval_ranks(4000);
  ASSERT_TRUE(ranks.has_value());
  EXPECT_EQ(ranks->low, 1938);
  EXPECT_EQ(ranks->high, 4001 - ranks->low);
  EXPECT_GE(ranks->confidence, 0.95);
  EXPECT_LT(ranks->confidence, 0.96);
}

TEST(MedianInterval, OrderStatisticsOfTheSample) {
  const MedianInterval m = median_interval({7, 3, 10, 1, 5, 9, 2, 8, 6, 4});
  EXPECT_EQ(m.median, 5.5);
  EXPECT_EQ(m.low, 2);
  EXPECT_EQ(m.high, 9);
  EXPECT_NEAR(m.confidence, 1 - 2 * 11.0 / 1024, 1e-12);
  const MedianInterval odd = median_interval({4, 1, 3, 2, 100, 5, 6});
  EXPECT_EQ(odd.median, 4);
  EXPECT_EQ(odd.low, 1);
  EXPECT_EQ(odd.high, 100);
  // Too few for 95 %: the whole range, and how confident it is.
  const MedianInterval three = median_interval({2, 1, 3});
  EXPECT_EQ(three.median, 2);
  EXPECT_EQ(three.low, 1);
  EXPECT_EQ(three.high, 3);
  EXPECT_EQ(three.confidence, 0.75);
  EXPECT_THROW(median_interval({}), std::invalid_argument);
}

}  // namespace
}  // namespace tuneray
