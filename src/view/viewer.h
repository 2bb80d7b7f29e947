// `tuneray view SCENE`: a window showing the scene path traced progressively in frame-budget
// mode, with a flying camera, camera-path playback and recording, a strip chart of frame
// times, quality switches and image saving (docs/viewer.md). Scripted with `frames` and
// `screenshot` for tests and screenshots.
#pragma once

#include <string>

#include "render/render_settings.h"
#include "view/view_tuner.h"

namespace tuneray {

struct ViewerOptions {
  std::string scene = "cornell";
  std::string scenes_dir;
  int width = 640, height = 360;
  std::string accel = "native";
  std::string bvh;
  int threads = 0;  // 0 = all cores
  uint64_t seed = 0;
  int max_bounces = 3;
  int camera = 0;
  // Frame budget of the rendering (ms); the rest of a frame (display, input) is a few ms, so
  // 25 ms gives about 30 frames per second at 640x360 (measured under Xvfb, docs/viewer.md).
  double frame_ms = 25;
  int path = -1;           // camera path to play back; -1 = none
  int path_frames = 240;   // frames the playback takes; it then holds the path's last camera
  int frames = 0;          // > 0: scripted, stop after this many frames
  std::string screenshot;  // scripted: write what the window shows after the last frame
  std::string record;      // write the cameras flown through as a camera path
  std::string save_prefix = "tuneray-view";  // of the images the save keys write
  float exposure = 0;
  bool chart = false;  // show the strip chart from the start
  bool quiet = false;
  QualityOptions quality;
  // Online tuning of the accelerator while viewing (`tune`'s tuner, database and keys); the
  // accelerator options are then the tuner's choice, not `accel`.
  bool tune = false;
  ViewTuneOptions tuning;
};

// Opens the window and runs until it is closed (Escape) or `frames` have been shown. Throws
// std::runtime_error with a one-line message when no window can be opened (no display) or the
// viewer was built without GLFW.
int run_viewer(const ViewerOptions& options);

// False when this build has no viewer (GLFW or OpenGL were missing at configure time).
bool viewer_available();

}  // namespace tuneray
