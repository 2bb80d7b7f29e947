// The arithmetic of the quality rows: medians over repeats, RMSE at the common time budget.
#include <algorithm>

#include "bench/equal_time.h"
#include "bench/quality_bench.h"
#include "tuning/stats.h"

namespace tuneray {

QualityRow summarize_runs(const std::string& name, const std::vector<FrameRun>& runs,
                          double budget_ms) {
  QualityRow r;
  r.name = name;
  const size_t frames = runs.front().rmse.size();
  auto per_frame = [&](std::vector<double> FrameRun::*field, size_t f) {
    std::vector<double> v;
    for (const FrameRun& run : runs) v.push_back((run.*field)[f]);
    return median(v);
  };
  for (size_t f = 0; f < frames; ++f) {
    r.time_ms.push_back(per_frame(&FrameRun::time_ms, f));
    r.spp.push_back(per_frame(&FrameRun::spp, f));
    r.rmse.push_back(per_frame(&FrameRun::rmse, f));
  }
  std::vector<double> ms_per_spp, mrays, at_budget, over;
  for (const FrameRun& run : runs) {
    ms_per_spp.push_back(run.time_ms.back() / std::max(run.spp.back(), 1e-9));
    mrays.push_back(run.mrays_per_s);
    at_budget.push_back(rmse_at_time(run.time_ms, run.rmse, budget_ms));
    over.push_back(run.time_ms.back() / budget_ms);
    r.rmse_repeats.push_back(run.rmse.back());
  }
  r.ms_per_spp = median(ms_per_spp);
  r.mrays_per_s = median(mrays);
  r.rmse_at_budget = median(at_budget);
  r.time_over_budget = median(over);
  return r;
}

}  // namespace tuneray
