// What the study reports per camera and per prediction. Every cost and ratio below the search's
// own frames comes from the camera's comparison (eval_comparison.h): all configurations
// compared at a camera measured in one interleaved window, so each ratio carries its 95 %
// confidence interval.
#pragma once

#include <string>
#include <vector>

#include "tuning/eval_profile.h"
#include "tuning/interleaved_ratios.h"

namespace tuneray {

inline constexpr int kMinYardstickFrames = 3;

// One camera's search and its comparison.
struct CameraRecord {
  std::string scene;
  std::string objective;
  int camera = 0;
  std::vector<double> search_ms;  // cost of every search frame, in order, as measured
  // The yardstick measured in both windows: the default configuration, which the search measures
  // in its first frame and every so often between its frames (EvalProfile::yardsticks) and the
  // comparison in every round. search_default_ms = the median of the search window's frames of
  // it (search_default_frames of them), search_window_load = that / the comparison's cost of it:
  // above 1, the machine was slower while the search ran than during the comparison, and every
  // search frame with it. With at least kMinYardstickFrames of them (search_calibrated) the
  // figures that set the search's frames against the comparison's costs (speedup over search,
  // overhead reduction, break-even) divide the search's frames by the load; a median of so few
  // frames is what one stopped frame cannot move. 0 when the search has no frame of the default.
  double search_default_ms = 0;
  int search_default_frames = 0;
  double search_window_load = 0;
  bool search_calibrated = false;
  // search_ms as if measured in the comparison's window (unchanged when not calibrated).
  std::vector<double> search_ms_in_comparison_window() const {
    std::vector<double> scaled = search_ms;
    if (search_calibrated)
      for (double& ms : scaled) ms /= search_window_load;
    return scaled;
  }
  std::string converged_config;  // the search's incumbent
  bool converged = false;
  // From the comparison (EvalComparison::cost_ms): the default's median cost times the median
  // per-round ratio to it (over the default, their ratios are the paired ratios below).
  double default_ms = 0;
  double converged_ms = 0;
  double native_ms = 0;  // native Embree, medium quality (`render --accel native`)
  double best_ms = 0;    // the fastest configuration of the comparison: the best known
  std::string best_config;
  RatioInterval search_speedup;  // default / converged
  RatioInterval native_speedup;  // native / converged
  int candidates = 0;            // distinct configurations compared
  int rounds = 0;
  bool within_target = false;  // every ratio's interval reached the target before the cap
};

// One predictor's choice for one validation camera in one repetition.
struct PredictionRecord {
  std::string scene;
  std::string objective;
  int repetition = 0;
  int camera = 0;
  std::string predictor;  // "nn" or "rbf"
  std::string config;
  double predicted_ms = 0;       // EvalComparison::cost_ms of the camera's comparison
  double search_total_ms = 0;    // accumulated time of the search's frames
  double speedup = 0;            // over the search, accumulated over the search's frame count
  RatioInterval native_speedup;  // native Embree / predicted
  double overhead_reduction = 0;
  RatioInterval roofline;  // best known / predicted
  double break_even = 0;   // frames; infinity = never
};

struct EvalResults {
  EvalProfile profile;
  std::vector<CameraRecord> cameras;
  std::vector<PredictionRecord> predictions;
};

}  // namespace tuneray
