// Checks a backend's batch entry point against its single-ray calls, ray by ray.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "accel/accel.h"

namespace tuneray::test {

// Every ray of the batch must get the hit the single-ray call gives, bit for bit (triangle, t,
// u, v). Returns how many rays hit.
inline size_t expect_batch_hits_are_single_ray_hits(const Accel& accel,
                                                    const std::vector<Ray>& rays,
                                                    RayCoherence coherence) {
  std::vector<Hit> hits(rays.size());
  accel.intersect_batch(rays, hits, coherence);
  size_t hit_count = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    Hit single;
    accel.intersect(rays[i], single);
    SCOPED_TRACE("ray " + std::to_string(i));
    EXPECT_EQ(single.prim, hits[i].prim);
    if (!single.valid()) continue;
    ++hit_count;
    EXPECT_EQ(single.t, hits[i].t);
    EXPECT_EQ(single.u, hits[i].u);
    EXPECT_EQ(single.v, hits[i].v);
  }
  return hit_count;
}

}  // namespace tuneray::test
