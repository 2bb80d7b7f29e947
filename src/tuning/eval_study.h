// The evaluation study (DESIGN §6): per scene and objective, a full search at every camera of a
// path (recorded in the tuning database, so an interrupted study resumes), then the predictors
// trained on a random 80 % of the cameras and judged on the other 20 %, repeated.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tuning/eval_profile.h"

namespace tuneray {

// One camera's search and its side-by-side re-measurements.
struct CameraRecord {
  std::string scene;
  std::string objective;
  int camera = 0;
  std::vector<double> search_ms;  // cost of every search frame, in order
  std::string converged_config;   // the search's incumbent
  bool converged = false;
  double default_ms = 0;  // live medians, measured the same way for every configuration
  double converged_ms = 0;
  double native_ms = 0;  // native Embree, medium quality (`render --accel native`)
  double best_ms = 0;    // best of every configuration measured live at this camera
  std::string best_config;
  double search_speedup() const { return converged_ms > 0 ? default_ms / converged_ms : 0.0; }
  double native_speedup() const { return converged_ms > 0 ? native_ms / converged_ms : 0.0; }
};

// One predictor's choice for one validation camera in one repetition.
struct PredictionRecord {
  std::string scene;
  std::string objective;
  int repetition = 0;
  int camera = 0;
  std::string predictor;  // "nn" or "rbf"
  std::string config;
  double predicted_ms = 0;
  double search_total_ms = 0;  // accumulated time of the search's frames
  double speedup = 0;          // over the search, accumulated over the search's frame count
  double native_speedup = 0;   // native Embree's live cost / predicted_ms
  double overhead_reduction = 0;
  double roofline = 0;
  double break_even = 0;  // frames; infinity = never
};

struct EvalResults {
  EvalProfile profile;
  std::vector<CameraRecord> cameras;
  std::vector<PredictionRecord> predictions;
};

struct EvalPaths {
  std::string out_dir;  // report, CSV, plots
  std::string db_path;  // tuning database (search data); default out_dir/eval.db
};

// Runs (or resumes) the study. `log` receives progress lines.
EvalResults run_eval_study(const EvalProfile& profile, const EvalPaths& paths,
                           const std::function<void(const std::string&)>& log);

}  // namespace tuneray
