// RMSE at equal time from a progressive run's frames (`bench quality`).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace tuneray {

// RMSE at time t along a run with cumulative frame times `time` (increasing) and the RMSE after
// each frame: between frames interpolated in log-log (an unbiased estimate's RMSE falls as
// t^-1/2, so the curve is nearly straight there), beyond the run's ends extrapolated with slope
// -1/2 from the nearest frame. Comparing every configuration at the same t keeps one that
// overruns its frames from buying its lower error with extra time.
inline double rmse_at_time(const std::vector<double>& time, const std::vector<double>& error,
                           double t) {
  if (t <= time.front()) return error.front() * std::sqrt(time.front() / t);
  if (t >= time.back()) return error.back() * std::sqrt(time.back() / t);
  size_t i = static_cast<size_t>(std::upper_bound(time.begin(), time.end(), t) - time.begin());
  double w = std::log(t / time[i - 1]) / std::log(time[i] / time[i - 1]);
  return std::exp(std::log(error[i - 1]) + w * std::log(error[i] / error[i - 1]));
}

}  // namespace tuneray
