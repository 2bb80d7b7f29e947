// What `tuneray tune` reports after a session: speedups over the default configuration and over
// native Embree, summarised across cameras, and the JSON report.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "tuning/tune_session.h"

namespace tuneray {

struct TuneSummary {
  double speedup_median = 0, speedup_geomean = 0;      // over the default configuration
  double vs_native_median = 0, vs_native_geomean = 0;  // over native Embree
  int searched = 0;       // cameras where the tuner searched rather than predicted
  int tuned = 0;          // cameras where the tuned BVH (not native) was chosen
  int capped = 0;         // cameras whose comparison reached the round cap before the target
  int race_changed = 0;   // cameras where the finalists' race overruled the tuner's best
  int race_frames = 0;    // frames the races took, over all cameras
  int search_frames = 0;  // frames the searches took, over all cameras
  int fallbacks = 0;      // cameras that kept a yardstick: the tuner's choice measured slower
};
TuneSummary summarize_tune(const TuneReport& report);

// `objective`, `scheduler` and `size` as given on the command line.
nlohmann::json tune_report_json(const TuneOptions& options, const std::string& objective,
                                const std::string& scheduler, const std::string& size,
                                const TuneReport& report);

}  // namespace tuneray
