// Pinhole / thin-lens camera description and camera paths (keyframes).
#pragma once

#include <string>
#include <vector>

#include "math/vec.h"

namespace tuneray {

struct CameraDesc {
  std::string name;
  Vec3f position{0, 0, 5};
  Vec3f target{0, 0, 0};
  Vec3f up{0, 1, 0};
  float vfov_deg = 45.0f;       // vertical field of view
  float lens_radius = 0.0f;     // 0 = pinhole
  float focus_distance = 0.0f;  // 0 = distance to target
};

// Keyframes of a camera path; issue 5 samples a spline through them.
struct CameraPath {
  std::string name;
  std::vector<CameraDesc> keyframes;
};

}  // namespace tuneray
