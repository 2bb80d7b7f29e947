// Ray sets and an agreement check between two accelerators (the tuned BVH against Embree
// native as the independent reference).
#pragma once

#include <string>
#include <vector>

#include "accel/accel.h"
#include "math/bbox.h"
#include "math/ray.h"

namespace tuneray::test {

struct RaySets {
  std::vector<Ray> closest;  // primary-like (from outside the box) and from surface points
  std::vector<Ray> shadow;   // surface point to surface point, segment
};

// `count` rays per kind, deterministic in `seed`.
RaySets make_ray_sets(const GeometryView& g, size_t count, uint64_t seed);

struct Agreement {
  size_t rays = 0;
  size_t hit_mismatch = 0;   // one hits, the other misses
  size_t dist_mismatch = 0;  // both hit, |t - t_ref| > 1e-5 relative
  size_t prim_mismatch = 0;  // both hit at the same distance but different triangles (no tie)
  size_t shadow_mismatch = 0;
  size_t hits = 0;
  std::string summary() const;
};

Agreement compare(const Accel& test, const Accel& reference, const RaySets& rays,
                  const GeometryView& g);

}  // namespace tuneray::test
