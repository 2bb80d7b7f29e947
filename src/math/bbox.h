// Axis-aligned bounding box.
#pragma once

#include "math/vec.h"

namespace tuneray {

struct BBox {
  Vec3f lo{kInf}, hi{-kInf};

  void extend(Vec3f p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void extend(const BBox& b) {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
  }
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  Vec3f extent() const { return empty() ? Vec3f(0) : hi - lo; }
  Vec3f center() const { return (lo + hi) * 0.5f; }
  float diagonal() const { return length(extent()); }
  float surface_area() const {
    Vec3f e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

}  // namespace tuneray
