// Rays and hit records shared by the accelerators and the integrator.
#pragma once

#include <cstdint>
#include <limits>

#include "math/vec.h"

namespace tuneray {

inline constexpr uint32_t kInvalidId = std::numeric_limits<uint32_t>::max();

struct Ray {
  Vec3f org;
  float tnear = 0;
  Vec3f dir;
  float tfar = kInf;
};

// Closest hit: prim indexes the scene's global triangle list; (u, v) are the barycentrics of
// vertices 1 and 2 (vertex 0 has weight 1 - u - v).
struct Hit {
  float t = kInf;
  uint32_t prim = kInvalidId;
  float u = 0, v = 0;
  bool valid() const { return prim != kInvalidId; }
};

}  // namespace tuneray
