// The viewer's entry point in builds without GLFW or OpenGL: `tuneray view` explains how to get
// it instead of failing to link.
#include <stdexcept>

#include "view/viewer.h"

namespace tuneray {

int run_viewer(const ViewerOptions&) {
  throw std::runtime_error(
      "view: this tuneray was built without the viewer (install libglfw3-dev and libgl-dev, "
      "then reconfigure)");
}

bool viewer_available() {
  return false;
}

}  // namespace tuneray
