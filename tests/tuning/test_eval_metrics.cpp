// The study's figures of merit on hand-made numbers.
#include <gtest/gtest.h>

#include "tuning/eval_metrics.h"
#include "tuning/stats.h"

namespace tuneray {
namespace {

// A search whose first frames explore slow configurations, then settles at 1.0 ms.
const std::vector<double> kSearch = {3.0, 2.0, 1.5, 1.0, 1.0};

TEST(EvalMetrics, AccumulatedSearchTimeExtendsWithTheConvergedCost) {
  EXPECT_DOUBLE_EQ(accumulated_search_time(kSearch, 1.0, 5), 8.5);
  EXPECT_DOUBLE_EQ(accumulated_search_time(kSearch, 1.0, 8), 11.5);
  EXPECT_DOUBLE_EQ(accumulated_search_time(kSearch, 1.0, 2), 5.0);
}

TEST(EvalMetrics, SpeedupAndOverhead) {
  // Prediction at 1.2 ms for 5 frames = 6.0 ms against the search's 8.5 ms.
  EXPECT_DOUBLE_EQ(prediction_speedup(kSearch, 1.0, 1.2, 5), 8.5 / 6.0);
  // Best 1.0: search overhead 3.5, prediction overhead 1.0 → reduction 1 - 1/3.5.
  EXPECT_DOUBLE_EQ(overhead_reduction(kSearch, 1.0, 1.2, 1.0, 5), 1.0 - 1.0 / 3.5);
  EXPECT_DOUBLE_EQ(overhead_reduction(kSearch, 1.0, 1.0, 1.0, 5), 1.0);
}

TEST(EvalMetrics, BreakEvenIsWhereTheSearchHasPaidForItsExploration) {
  // Prediction 2.5 ms/frame: after 3 frames search 6.5 <= 7.5.
  EXPECT_DOUBLE_EQ(break_even_frame(kSearch, 1.0, 2.5), 2.0);  // 5.0 <= 5.0 at frame 2
  // Prediction 1.2: search 8.5 vs 6.0 after 5 frames; gains 0.2 per frame → 13 more frames.
  EXPECT_DOUBLE_EQ(break_even_frame(kSearch, 1.0, 1.2), 5.0 + 13.0);
  // A prediction as fast as the converged search is never caught up with.
  EXPECT_EQ(break_even_frame(kSearch, 1.0, 1.0), kNever);
}

TEST(Stats, MedianQuantileAndGeometricMean) {
  EXPECT_DOUBLE_EQ(median({3, 1, 2}), 2.0);
  EXPECT_DOUBLE_EQ(median({4, 1, 2, 3}), 2.5);
  EXPECT_DOUBLE_EQ(quantile({0, 10}, 0.25), 2.5);
  EXPECT_NEAR(geometric_mean({1, 4, 16}), 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(median({}), 0.0);
}

}  // namespace
}  // namespace tuneray
