// Equal-time RMSE: exact on the curve an unbiased estimator follows, and a plain log-log line
// between frames otherwise.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/equal_time.h"

namespace tuneray {
namespace {

TEST(EqualTime, ExactOnAnInverseSquareRootCurve) {
  std::vector<double> time = {100, 230, 390, 800}, error;
  for (double t : time) error.push_back(3.0 / std::sqrt(t));
  for (double t : {10.0, 100.0, 150.0, 230.0, 500.0, 800.0, 2000.0})
    EXPECT_NEAR(rmse_at_time(time, error, t), 3.0 / std::sqrt(t), 1e-12) << t;
}

TEST(EqualTime, StraightLineInLogLogBetweenFrames) {
  std::vector<double> time = {10, 1000}, error = {1.0, 0.01};  // slope -1 in log-log
  EXPECT_NEAR(rmse_at_time(time, error, 100), 0.1, 1e-12);
  // Past the last frame the slope is -1/2, whatever the run's own slope was.
  EXPECT_NEAR(rmse_at_time(time, error, 4000), 0.005, 1e-12);
}

}  // namespace
}  // namespace tuneray
