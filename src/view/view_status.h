// The viewer's title line: speed, samples and the active switches, in one line a window
// manager can show.
#pragma once

#include <string>

#include "view/view_tuner.h"

namespace tuneray {

struct ViewStatus {
  std::string scene;
  double frame_ms = 0;   // smoothed wall time of a whole frame (render + display)
  double render_ms = 0;  // of the frame budget's passes alone
  double frame_spp = 0;  // samples per pixel the last frame added
  double film_spp = 0;   // samples per pixel accumulated since the last camera change
  bool adaptive = false;
  std::string sampler;  // "bluenoise" or "pcg"
  std::string accel;    // backend and configuration in use
  bool playing_path = false;
  std::string tuning;  // the tuner's mode, speedups and configuration; empty when not tuning
};

// "cornell | 31.0 ms/frame (32.3 fps, render 28.0 ms) | 2.10 spp/frame, 84.0 spp | adaptive,
// bluenoise | native", then " | " and the tuning text when tuning.
std::string format_title(const ViewStatus& status);
// "search 0.412 ms/spp, 1.08x over default, 0.97x over native | backend=tuned,..." ("-" for a
// yardstick not measured yet at this camera).
std::string format_tuning(const ViewTuneStatus& tuning);

}  // namespace tuneray
