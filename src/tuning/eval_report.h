// Writes the study's results: raw CSV files, summary tables in report.md beside the published
// figures, and gnuplot plots (PNG and SVG).
#pragma once

#include <string>
#include <vector>

#include "tuning/eval_study.h"

namespace tuneray {

// A typical 95 % interval of a ratio summarised over cameras or predictions: the same statistic
// as the ratio's (median or mean) of the single comparisons' bounds. It says how tightly each
// comparison pinned its ratio down, not how uncertain the statistic over cameras is.
struct TypicalInterval {
  double low = 0, high = 0;
};

// Per scene and objective, the aggregated figures shown in the report.
struct EvalSummary {
  std::string scene, objective;
  int cameras = 0;
  int within_target = 0;     // comparisons whose every interval reached the target before the cap
  double rounds_median = 0;  // rounds per comparison
  double search_speedup_median = 0;         // default / converged, over cameras
  double search_native_speedup_median = 0;  // native Embree / converged, over cameras
  TypicalInterval search_speedup_interval, search_native_speedup_interval;
  // The searches' window against the comparisons' (CameraRecord::search_window_load), median over
  // the cameras that have a yardstick, and how many cameras' search frames were calibrated by it.
  double search_window_load_median = 0;
  int search_calibrated = 0;
  double nn_speedup_geomean = 0;  // prediction over search, accumulated frames
  double rbf_speedup_geomean = 0;
  double nn_overhead_reduction_median = 0;
  double rbf_overhead_reduction_median = 0;
  double nn_roofline_mean = 0;
  double rbf_roofline_mean = 0;
  TypicalInterval nn_roofline_interval, rbf_roofline_interval;
  double nn_break_even_median = 0;  // over the finite ones
  double rbf_break_even_median = 0;
  int nn_never = 0, rbf_never = 0;      // predictions the search never catches up with
  double nn_native_speedup_median = 0;  // native Embree / predicted, over predictions
  double rbf_native_speedup_median = 0;
  TypicalInterval nn_native_speedup_interval, rbf_native_speedup_interval;
};

std::vector<EvalSummary> summarise(const EvalResults& results);

// Numbers in the CSV files, the report and the figures' data share one format (3 decimals,
// "inf"), so the report can be checked against the CSV.
std::string report_number(double v);

// Writes cameras.csv, search_frames.csv, predictions.csv, summary.csv, report.md and plots/ in
// `out_dir`. Plots need gnuplot; without it the report says so. Returns the report's path.
std::string write_eval_report(const EvalResults& results, const std::string& out_dir,
                              const std::string& command_line);

}  // namespace tuneray
