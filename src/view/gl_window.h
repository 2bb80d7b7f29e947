// A GLFW window with a legacy OpenGL context, just enough for the viewer: draw an RGB image
// filling the window, draw a strip chart over it, read back what is shown. Legacy OpenGL
// (glDrawPixels, immediate-mode lines) needs no extension loader.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "view/frame_chart.h"

struct GLFWwindow;

namespace tuneray {

class GlWindow {
 public:
  // Throws std::runtime_error with GLFW's reason (one line) when no window can be opened, e.g.
  // without a display.
  GlWindow(int width, int height, const std::string& title);
  ~GlWindow();
  GlWindow(const GlWindow&) = delete;
  GlWindow& operator=(const GlWindow&) = delete;

  GLFWwindow* handle() const { return window_; }
  bool should_close() const;
  void set_title(const std::string& title);

  // `rgb`: width x height 8-bit pixels, rows top to bottom, scaled to fill the window.
  void draw_image(const std::vector<uint8_t>& rgb, int width, int height);
  // The chart in the bottom quarter of the window: a dark band, the budget line and the
  // frame times.
  void draw_chart(const std::vector<ChartPoint>& points, float budget_y);
  // What the next present() shows, 8-bit RGB, rows top to bottom; sets width and height.
  std::vector<uint8_t> read_pixels(int& width, int& height) const;
  void present();
  // Runs the input callbacks of the events that arrived since the last call.
  void poll_events();

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace tuneray
