#include "view/gl_window.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <stdexcept>

namespace tuneray {

namespace {

// GLFW reports failures through a callback; the last one becomes the exception's message.
std::string& last_glfw_error() {
  static std::string message;
  return message;
}

void remember_glfw_error(int, const char* description) {
  last_glfw_error() = description ? description : "unknown GLFW error";
}

std::runtime_error window_error(const std::string& what) {
  std::string reason = last_glfw_error().empty() ? "no reason given" : last_glfw_error();
  return std::runtime_error("view: " + what + " (" + reason +
                            "); run it on a desktop or under xvfb-run");
}

}  // namespace

GlWindow::GlWindow(int width, int height, const std::string& title) {
  glfwSetErrorCallback(remember_glfw_error);
  if (!glfwInit()) throw window_error("cannot open a window: no display");
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw window_error("cannot open a " + std::to_string(width) + "x" + std::to_string(height) +
                       " OpenGL window");
  }
  glfwMakeContextCurrent(window_);
  // The frame budget paces the frames; waiting for vertical sync as well would halve the rate
  // whenever a frame overruns a refresh.
  glfwSwapInterval(0);
}

GlWindow::~GlWindow() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool GlWindow::should_close() const {
  return glfwWindowShouldClose(window_);
}

void GlWindow::set_title(const std::string& title) {
  glfwSetWindowTitle(window_, title.c_str());
}

void GlWindow::draw_image(const std::vector<uint8_t>& rgb, int width, int height) {
  int fb_width = 0, fb_height = 0;
  glfwGetFramebufferSize(window_, &fb_width, &fb_height);
  glViewport(0, 0, fb_width, fb_height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // Rows arrive top first while OpenGL draws bottom up: start at the top-left corner and zoom
  // by a negative height.
  glRasterPos2f(-1.0f, 1.0f);
  glPixelZoom(static_cast<float>(fb_width) / static_cast<float>(width),
              -static_cast<float>(fb_height) / static_cast<float>(height));
  glDrawPixels(width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
}

void GlWindow::draw_chart(const std::vector<ChartPoint>& points, float budget_y) {
  // The chart's band in normalised device coordinates: the bottom quarter, 2% margins.
  const float left = -0.98f, right = 0.98f, bottom = -0.98f, top = -0.5f;
  auto x_of = [&](float x) { return left + x * (right - left); };
  auto y_of = [&](float y) { return bottom + y * (top - bottom); };
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glColor4f(0, 0, 0, 0.6f);
  glBegin(GL_QUADS);
  glVertex2f(left, bottom);
  glVertex2f(right, bottom);
  glVertex2f(right, top);
  glVertex2f(left, top);
  glEnd();
  glDisable(GL_BLEND);
  glColor3f(1.0f, 0.3f, 0.3f);
  glBegin(GL_LINES);
  glVertex2f(left, y_of(budget_y));
  glVertex2f(right, y_of(budget_y));
  glEnd();
  glBegin(GL_LINE_STRIP);
  for (const ChartPoint& p : points) {
    switch (p.kind) {
      case FrameKind::kPlain:
      case FrameKind::kExploit:
        glColor3f(0.3f, 1.0f, 0.4f);  // green
        break;
      case FrameKind::kSearch:
        glColor3f(1.0f, 0.85f, 0.2f);  // yellow
        break;
      case FrameKind::kYardstick:
        glColor3f(0.4f, 0.6f, 1.0f);  // blue
        break;
    }
    glVertex2f(x_of(p.x), y_of(p.y));
  }
  glEnd();
  glColor3f(1, 1, 1);
}

std::vector<uint8_t> GlWindow::read_pixels(int& width, int& height) const {
  glfwGetFramebufferSize(window_, &width, &height);
  std::vector<uint8_t> bottom_up(static_cast<size_t>(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottom_up.data());
  std::vector<uint8_t> top_down(bottom_up.size());
  const size_t row = static_cast<size_t>(width) * 3;
  for (int y = 0; y < height; ++y)
    std::copy_n(bottom_up.begin() + static_cast<std::ptrdiff_t>(row * (height - 1 - y)), row,
                top_down.begin() + static_cast<std::ptrdiff_t>(row * y));
  return top_down;
}

void GlWindow::present() {
  glfwSwapBuffers(window_);
}

void GlWindow::poll_events() {
  glfwPollEvents();
}

}  // namespace tuneray
