// The study's figures of merit (DESIGN §6), as pure functions of measured costs, so they can be
// tested on made-up numbers. The ratios between configurations (search speedup, roofline, over
// native) are paired ratios of a camera's comparison (eval_comparison.h).
#pragma once

#include <limits>
#include <vector>

namespace tuneray {

inline constexpr double kNever = std::numeric_limits<double>::infinity();

// Accumulated time of `frames` frames when searching: the measured costs of the search frames in
// order (frames beyond them run the search's converged configuration at `converged_cost`).
double accumulated_search_time(const std::vector<double>& search_costs, double converged_cost,
                               int frames);

// Speedup of the prediction over the search for the accumulated time of `frames` frames.
double prediction_speedup(const std::vector<double>& search_costs, double converged_cost,
                          double predicted_cost, int frames);

// 1 - overhead(prediction) / overhead(search), where overhead is the accumulated time above
// `frames` frames at the best known cost. 1 = the prediction has no overhead at all; 0 = as
// much as the search; negative = more.
double overhead_reduction(const std::vector<double>& search_costs, double converged_cost,
                          double predicted_cost, double best_cost, int frames);

// The first frame count k at which the search's accumulated time is no longer above the
// prediction's (k x predicted_cost), i.e. the search has paid for its exploration. Beyond the
// measured frames the search runs at converged_cost. kNever when it never pays off.
double break_even_frame(const std::vector<double>& search_costs, double converged_cost,
                        double predicted_cost);

}  // namespace tuneray
