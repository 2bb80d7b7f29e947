// `tuneray view` as a user runs it: without a display, and scripted under Xvfb with Mesa's
// software OpenGL, flying a camera path and comparing the screenshot with an offline render.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/run_program.h"
#include "common/temp_dir.h"
#include "image/io.h"
#include "offline_render.h"
#include "scene/camera_spline.h"
#include "scene/load.h"
#include "view/viewer.h"

namespace tuneray {
namespace {

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::string dirs = path;
  size_t start = 0;
  while (start <= dirs.size()) {
    size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    if (std::filesystem::exists(std::filesystem::path(dirs.substr(start, end - start)) / program))
      return true;
    start = end + 1;
  }
  return false;
}

size_t line_count(const std::string& text) {
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

const std::map<std::string, std::optional<std::string>> kNoDisplay = {
    {"DISPLAY", std::nullopt}, {"WAYLAND_DISPLAY", std::nullopt}};

// Mesa's drivers are loaded and unloaded with dlopen, and what they keep until exit shows as
// leaks from "<unknown module>", which no suppression can name. In sanitizer builds the child
// that opens a GL context therefore runs without the leak check (every other ASan and UBSan
// check stays on); the viewer's own classes are leak-checked in process by the other tests.
const std::map<std::string, std::optional<std::string>> kMesaChild = {
    {"LSAN_OPTIONS", "detect_leaks=0"}};

TEST(ViewerWindow, WithoutADisplayFailsWithOneLine) {
  testing::ProgramResult r = testing::run_program(
      {testing::tuneray_binary(), "view", "cornell", "--frames", "1"}, kNoDisplay);
  ASSERT_FALSE(r.signaled) << r.output;
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(line_count(r.output), 1u) << r.output;
  if (viewer_available())
    EXPECT_NE(r.output.find("no display"), std::string::npos) << r.output;
  else
    EXPECT_NE(r.output.find("built without the viewer"), std::string::npos) << r.output;
}

TEST(ViewerWindow, BadOptionsFailBeforeOpeningAWindow) {
  testing::ProgramResult r = testing::run_program(
      {testing::tuneray_binary(), "view", "cornell", "--screenshot", "x.png"}, kNoDisplay);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("--screenshot needs --frames"), std::string::npos) << r.output;
  r = testing::run_program(
      {testing::tuneray_binary(), "view", "cornell", "--frames", "1", "--screenshot", "x.jpg"},
      kNoDisplay);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(line_count(r.output), 1u) << r.output;
  EXPECT_NE(r.output.find("x.jpg"), std::string::npos) << r.output;
}

// Flies path 0 of the Cornell box in 6 frames, holds its last camera for 34 more, and checks
// the screenshot against an offline render of the last camera of the recorded path.
TEST(ViewerWindow, ScreenshotOfARecordedFlightMatchesAnOfflineRender) {
  if (!viewer_available()) GTEST_SKIP() << "built without the viewer (no GLFW/OpenGL)";
  if (!on_path("xvfb-run")) GTEST_SKIP() << "xvfb-run not installed (Debian package xvfb)";
  testing::TempDir dir;
  const std::string shot = dir.file("shot.png"), path_file = dir.file("flight.json");
  const int width = 160, height = 90;
  testing::ProgramResult r = testing::run_program({"xvfb-run",
                                                   "-a",
                                                   "-s",
                                                   "-screen 0 640x480x24",
                                                   testing::tuneray_binary(),
                                                   "view",
                                                   "cornell",
                                                   "--size",
                                                   "160x90",
                                                   "--path",
                                                   "0",
                                                   "--path-frames",
                                                   "6",
                                                   "--frames",
                                                   "40",
                                                   "--frame-ms",
                                                   "40",
                                                   "--screenshot",
                                                   shot,
                                                   "--record",
                                                   path_file},
                                                  kMesaChild);
  ASSERT_FALSE(r.signaled) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // The recorded path is the played one: its six samples, the last the path's last keyframe.
  Scene scene = load_scene("cornell");
  std::vector<CameraDesc> played = sample_camera_path(scene.camera_paths[0], 6);
  nlohmann::json recorded = nlohmann::json::parse(std::ifstream(path_file));
  ASSERT_EQ(recorded["keyframes"].size(), played.size());
  const nlohmann::json& last = recorded["keyframes"].back();
  CameraDesc camera = played.back();
  for (int i = 0; i < 3; ++i) {
    EXPECT_FLOAT_EQ(last["position"][i].get<float>(), camera.position[i]);
    EXPECT_FLOAT_EQ(last["target"][i].get<float>(), camera.target[i]);
  }
  camera.position = Vec3f(last["position"][0], last["position"][1], last["position"][2]);
  camera.target = Vec3f(last["target"][0], last["target"][1], last["target"][2]);

  ReadOptions raw;
  raw.srgb_to_linear = false;
  Image image = read_image(shot, raw);
  ASSERT_EQ(image.width(), width);
  ASSERT_EQ(image.height(), height);
  std::vector<uint8_t> shown;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        shown.push_back(static_cast<uint8_t>(std::lround(image.at(x, y)[c] * 255.0f)));
  const double same = testing::display_rmse(
      shown, testing::offline_display_bytes(scene, camera, width, height, 64));
  const double first = testing::display_rmse(
      shown, testing::offline_display_bytes(scene, played.front(), width, height, 64));
  std::cout << "screenshot RMSE against the offline render: " << same
            << " (against the path's first camera: " << first << ")\n";
  EXPECT_LT(same, 0.05);
  EXPECT_GT(first, 3 * same);
}

}  // namespace
}  // namespace tuneray
