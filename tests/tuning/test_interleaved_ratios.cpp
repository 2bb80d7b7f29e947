#include "tuning/interleaved_ratios.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace tuneray {
namespace {

TEST(StudentT95, TableAndExpansionAgreeWithPublishedQuantiles) {
  EXPECT_EQ(student_t95(1), 12.706);
  EXPECT_EQ(student_t95(2), 4.303);
  EXPECT_EQ(student_t95(30), 2.042);
  EXPECT_NEAR(student_t95(31), 2.0395, 0.001);
  EXPECT_NEAR(student_t95(60), 2.0003, 0.001);
  EXPECT_NEAR(student_t95(120), 1.9799, 0.001);
  EXPECT_NEAR(student_t95(100000), 1.95998, 0.0001);
  EXPECT_THROW(student_t95(0), std::invalid_argument);
}

TEST(MeasureInterleaved, ConstantCostsGiveTheExactRatioAfterTheMinimumRounds) {
  const double base[3] = {10, 20, 5};
  InterleavedResult r = measure_interleaved(3, 0, [&](int i) { return base[i]; });
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.rounds, 3);
  EXPECT_DOUBLE_EQ(r.ratios[0].ratio, 1.0);
  EXPECT_DOUBLE_EQ(r.ratios[1].ratio, 2.0);
  EXPECT_DOUBLE_EQ(r.ratios[2].ratio, 0.5);
  EXPECT_DOUBLE_EQ(r.ratios[1].low, 2.0);
  EXPECT_DOUBLE_EQ(r.ratios[1].high, 2.0);
  EXPECT_EQ(r.ratios[2].median_cost, 5.0);
}

TEST(MeasureInterleaved, OrderRotatesEveryRound) {
  std::vector<int> order;
  InterleavedOptions o;
  o.min_rounds = 3;
  o.max_rounds = 3;
  measure_interleaved(
      3, 1,
      [&](int i) {
        order.push_back(i);
        return 1.0;
      },
      o);
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 1, 2, 0, 2, 0, 1}));
}

TEST(MeasureInterleaved, ASlowingMachineDoesNotMoveTheRatio) {
  // Every cost doubles, then triples, ... from round to round (a machine getting busier): the
  // medians of separate runs would drift, the paired ratio stays exact.
  int calls = 0;
  InterleavedResult r = measure_interleaved(2, 1, [&](int i) {
    const int round = calls++ / 2;
    return (i == 0 ? 3.0 : 2.0) * (1 + round);
  });
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.ratios[0].ratio, 1.5, 1e-12);
  EXPECT_NEAR(r.ratios[0].relative_half_width(), 0.0, 1e-12);
}

TEST(MeasureInterleaved, NoiseNeedsMoreRoundsAndTheCapStopsThem) {
  // Deterministic ±10 % noise on candidate 0 (a fixed pseudo-random sequence).
  auto noisy = [](int cap) {
    unsigned state = 12345;
    InterleavedOptions o;
    o.max_rounds = cap;
    return measure_interleaved(
        2, 1,
        [&](int i) {
          state = state * 1103515245u + 12345u;
          const double u = ((state >> 8) & 0xffff) / 65535.0;
          return i == 0 ? 4.0 * (0.9 + 0.2 * u) : 2.0;
        },
        o);
  };
  InterleavedResult capped = noisy(3);
  EXPECT_FALSE(capped.converged);
  EXPECT_EQ(capped.rounds, 3);
  EXPECT_GT(capped.ratios[0].relative_half_width(), 0.03);
  InterleavedResult enough = noisy(200);
  EXPECT_TRUE(enough.converged);
  EXPECT_GT(enough.rounds, 3);
  EXPECT_LE(enough.ratios[0].relative_half_width(), 0.03);
  EXPECT_LT(enough.ratios[0].low, enough.ratios[0].ratio);
  EXPECT_GT(enough.ratios[0].high, enough.ratios[0].ratio);
  EXPECT_NEAR(enough.ratios[0].ratio, 2.0, 0.06);
}

TEST(MeasureInterleaved, AnyTwoCandidatesCompareOverTheSameRounds) {
  const double base[3] = {10, 20, 5};
  int calls = 0;
  InterleavedResult r = measure_interleaved(3, 0, [&](int i) {
    return base[i] * (1 + 0.1 * (calls++ / 3));  // the machine slows from round to round
  });
  ASSERT_EQ(r.costs.size(), 3u);
  EXPECT_EQ(r.costs[1].size(), static_cast<size_t>(r.rounds));
  const RatioInterval fast_over_slow = paired_ratio(r, 2, 1);
  EXPECT_NEAR(fast_over_slow.ratio, 0.25, 1e-12);
  EXPECT_NEAR(fast_over_slow.low, 0.25, 1e-12);
  EXPECT_EQ(fast_over_slow.median_cost, r.ratios[2].median_cost);
  EXPECT_THROW(paired_ratio(r, 0, 3), std::invalid_argument);
}

TEST(MeasureInterleaved, EveryPairWaitsForTheRatiosBetweenCandidatesToo) {
  // Candidates 1 and 2 wobble in opposite directions by ±0.8 % around the reference each round:
  // each ratio to the reference is within ±3 % after 3 rounds, the ratio between 1 and 2 (twice
  // the wobble) is not.
  auto wobbling = [](bool every_pair, int cap) {
    int calls = 0;
    InterleavedOptions o;
    o.every_pair = every_pair;
    o.max_rounds = cap;
    return measure_interleaved(
        3, 0,
        [&](int i) {
          const double sign = (calls++ / 3) % 2 ? -1.0 : 1.0;
          return i == 0 ? 1.0 : std::exp((i == 1 ? 0.008 : -0.008) * sign) * (i == 1 ? 2 : 3);
        },
        o);
  };
  const InterleavedResult to_reference = wobbling(false, 30);
  EXPECT_TRUE(to_reference.converged);
  EXPECT_EQ(to_reference.rounds, 3);
  EXPECT_GT(paired_ratio(to_reference, 1, 2).relative_half_width(), 0.03);
  const InterleavedResult pairs = wobbling(true, 30);
  EXPECT_TRUE(pairs.converged);
  EXPECT_GT(pairs.rounds, 3);
  EXPECT_LE(paired_ratio(pairs, 1, 2).relative_half_width(), 0.03);
  EXPECT_LE(paired_ratio(pairs, 2, 1).relative_half_width(), 0.03);
  EXPECT_FALSE(wobbling(true, 3).converged);
}

TEST(MeasureInterleaved, RefusesBadArgumentsAndBadCosts) {
  auto one = [](int) { return 1.0; };
  EXPECT_THROW(measure_interleaved(2, 2, one), std::invalid_argument);
  EXPECT_THROW(measure_interleaved(0, 0, one), std::invalid_argument);
  InterleavedOptions o;
  o.min_rounds = 5;
  o.max_rounds = 4;
  EXPECT_THROW(measure_interleaved(2, 0, one, o), std::invalid_argument);
  EXPECT_THROW(measure_interleaved(2, 0, [](int i) { return i == 1 ? 0.0 : 1.0; }),
               std::invalid_argument);
  EXPECT_THROW(
      measure_interleaved(2, 0, [](int) { return std::numeric_limits<double>::quiet_NaN(); }),
      std::invalid_argument);
}

}  // namespace
}  // namespace tuneray
