#include "tuning/interleaved_ratios.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

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

InterleavedResult fixed_rounds(const std::vector<std::vector<double>>& costs) {
  InterleavedResult r;
  r.costs = costs;
  r.rounds = static_cast<int>(costs.front().size());
  return r;
}

// One frame of candidate 0 stopped for a while (SIGSTOP, a load spike): 30 times its cost in one
// round of 30. The geometric mean moves by 30^(1/30) = 12 %; the median does not move at all.
TEST(PairedRatio, OneStoppedFrameMovesTheGeometricMeanNotTheMedian) {
  std::vector<std::vector<double>> costs(2);
  for (int round = 0; round < 30; ++round) {
    const double load = 1 + 0.01 * (round % 7);  // a common load, as in interleaved rounds
    costs[0].push_back((round == 17 ? 30 : 1) * 6.0 * load);
    costs[1].push_back(3.0 * load);
  }
  const InterleavedResult r = fixed_rounds(costs);
  const RatioInterval geometric = paired_ratio(r, 0, 1);
  EXPECT_NEAR(geometric.ratio, 2.0 * std::pow(30.0, 1.0 / 30), 1e-12);
  const RatioInterval median = paired_ratio(r, 0, 1, RatioEstimator::kMedian);
  EXPECT_NEAR(median.ratio, 2.0, 1e-15);
  EXPECT_NEAR(median.low, 2.0, 1e-15);  // ranks 10 and 21 of 30: the stopped round is the 30th
  EXPECT_NEAR(median.high, 2.0, 1e-15);
  EXPECT_NEAR(median.confidence, 1 - 2 * 22964087.0 / 1073741824.0, 1e-12);
  EXPECT_NEAR(median.relative_half_width(), 0.0, 1e-15);
}

TEST(PairedRatio, TheMedianIsTheMiddleRatioAndItsIntervalTheRankedRatios) {
  // Ratios 1.1, 0.9, 1.3, 1.0, 1.2, 0.8, 1.4, 1.05, 0.95, 1.15 (round by round): sorted
  // 0.8 0.9 0.95 1.0 1.05 1.1 1.15 1.2 1.3 1.4, median sqrt(1.05 * 1.1) (the geometric mean of
  // the two middle ratios, so that the pair inverts exactly), interval ranks 2 and 9.
  const std::vector<double> ratios = {1.1, 0.9, 1.3, 1.0, 1.2, 0.8, 1.4, 1.05, 0.95, 1.15};
  std::vector<std::vector<double>> costs(2);
  for (size_t k = 0; k < ratios.size(); ++k) {
    costs[1].push_back(2.0 + static_cast<double>(k));
    costs[0].push_back(ratios[k] * costs[1].back());
  }
  const InterleavedResult r = fixed_rounds(costs);
  const RatioInterval m = paired_ratio(r, 0, 1, RatioEstimator::kMedian);
  EXPECT_NEAR(m.ratio, std::sqrt(1.05 * 1.1), 1e-12);
  EXPECT_NEAR(m.low, 0.9, 1e-12);
  EXPECT_NEAR(m.high, 1.3, 1e-12);
  EXPECT_NEAR(m.relative_half_width(), 1.3 / std::sqrt(1.05 * 1.1) - 1, 1e-12);  // the wider side
  const RatioInterval inverse = paired_ratio(r, 1, 0, RatioEstimator::kMedian);
  EXPECT_NEAR(inverse.ratio, 1 / m.ratio, 1e-12);
  EXPECT_NEAR(inverse.low, 1 / m.high, 1e-12);
  EXPECT_NEAR(inverse.high, 1 / m.low, 1e-12);
}

TEST(MeasureInterleaved, TheMedianStopsOnlyWithA95PercentIntervalWithinTheTarget) {
  InterleavedOptions o;
  o.estimator = RatioEstimator::kMedian;
  // Constant costs: exact from the first round, but no median has a 95 % interval under 6.
  const double base[3] = {10, 20, 5};
  const InterleavedResult flat = measure_interleaved(
      3, 0, [&](int i) { return base[i]; }, o);
  EXPECT_TRUE(flat.converged);
  EXPECT_EQ(flat.rounds, 6);
  EXPECT_DOUBLE_EQ(flat.ratios[1].ratio, 2.0);
  EXPECT_GE(flat.ratios[1].confidence, 0.95);

  // Candidate 1 stopped 30 times too long in round 2: the range of 6, 7 or 8 rounds holds it,
  // ranks 2 and 8 of 9 leave it out, and the ratio is exact.
  o.every_pair = true;
  int calls = 0;
  const InterleavedResult stopped = measure_interleaved(
      2, 0,
      [&](int i) {
        const int round = calls++ / 2;
        return i == 0 ? 4.0 : (round == 2 ? 30.0 : 1.0) * 2.0;
      },
      o);
  EXPECT_TRUE(stopped.converged);
  EXPECT_EQ(stopped.rounds, 9);
  EXPECT_DOUBLE_EQ(stopped.ratios[1].ratio, 0.5);
  EXPECT_DOUBLE_EQ(stopped.ratios[1].low, 0.5);
  EXPECT_DOUBLE_EQ(stopped.ratios[1].high, 0.5);
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
