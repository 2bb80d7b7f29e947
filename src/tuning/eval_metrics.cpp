#include "tuning/eval_metrics.h"

#include <cmath>

namespace tuneray {

double accumulated_search_time(const std::vector<double>& search_costs, double converged_cost,
                               int frames) {
  double total = 0;
  for (int k = 0; k < frames; ++k)
    total += k < static_cast<int>(search_costs.size()) ? search_costs[k] : converged_cost;
  return total;
}

double prediction_speedup(const std::vector<double>& search_costs, double converged_cost,
                          double predicted_cost, int frames) {
  double predicted = predicted_cost * frames;
  return predicted > 0 ? accumulated_search_time(search_costs, converged_cost, frames) / predicted
                       : 0.0;
}

double overhead_reduction(const std::vector<double>& search_costs, double converged_cost,
                          double predicted_cost, double best_cost, int frames) {
  double ideal = best_cost * frames;
  double search_overhead = accumulated_search_time(search_costs, converged_cost, frames) - ideal;
  double predicted_overhead = predicted_cost * frames - ideal;
  if (!(search_overhead > 0)) return predicted_overhead <= 0 ? 1.0 : -kNever;
  return 1.0 - predicted_overhead / search_overhead;
}

double break_even_frame(const std::vector<double>& search_costs, double converged_cost,
                        double predicted_cost) {
  double search = 0;
  const int n = static_cast<int>(search_costs.size());
  for (int k = 1; k <= n; ++k) {
    search += search_costs[k - 1];
    if (search <= predicted_cost * k) return k;
  }
  // After the measured frames both accumulate linearly: solve search + j c_s <= (n + j) c_p.
  double gain_per_frame = predicted_cost - converged_cost;
  if (!(gain_per_frame > 0)) return kNever;
  double deficit = search - predicted_cost * n;
  return n + std::ceil(deficit / gain_per_frame);
}

}  // namespace tuneray
