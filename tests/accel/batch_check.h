// Checks a backend's batch entry point against its single-ray calls, ray by ray.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "accel/accel.h"

namespace tuneray::test {

// Tuned-BVH configurations that cover every choice of batch kernel: packets and streams (4- and
// 8-wide fast trees, small leaves, spatial splits with the static relayout) and the single-ray
// loop of the trees that have neither (2-wide, compact, robust).
inline const char* const kBatchKernelConfigs[] = {
    "branching=8,sah_block_size=4,min_leaf=4,max_leaf=28",  // Embree's BVH8 settings
    "branching=4,sah_block_size=4,min_leaf=4,max_leaf=28",
    "branching=8,max_leaf=4",
    "branching=8,max_leaf=1",
    "branching=8,quality=high,static=1",
    "branching=2",
    "branching=8,compact=1",
    "branching=8,robust=1",
    "branching=4,robust=1",
    "branching=2,collapse=1",
    "branching=4,max_leaf=4,collapse=1",
    "branching=2,sah_block_size=4,min_leaf=4,max_leaf=28,reinsert=1",
    "branching=2,sah_block_size=4,min_leaf=4,max_leaf=28,reinsert=1,optimal_collapse=1",
};

// Every ray of the batch must get the single-ray call's triangle, and its t within
// `relative_t` * t and its u and v within `barycentric` (bit for bit where these are 0).
// Returns how many rays hit.
inline size_t expect_batch_hits_within(const Accel& accel, const std::vector<Ray>& rays,
                                       RayCoherence coherence, float relative_t,
                                       float barycentric) {
  const auto expect_close = [](float single, float batch, float tolerance) {
    if (tolerance == 0)
      EXPECT_EQ(single, batch);
    else
      EXPECT_NEAR(single, batch, tolerance);
  };
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
    expect_close(single.t, hits[i].t, relative_t * single.t);
    expect_close(single.u, hits[i].u, barycentric);
    expect_close(single.v, hits[i].v, barycentric);
  }
  return hit_count;
}

// Bit for bit (triangle, t, u, v): our kernels and native Embree's default.
inline size_t expect_batch_hits_are_single_ray_hits(const Accel& accel,
                                                    const std::vector<Ray>& rays,
                                                    RayCoherence coherence) {
  return expect_batch_hits_within(accel, rays, coherence, 0, 0);
}

// To rounding, for native Embree's other triangle BVHs, whose stream intersectors compute the
// hit another way than their single-ray ones on some CPUs (bvh4.triangle4v on an AMD EPYC with
// AVX2: u and v 2e-6 to 1.5e-5 apart at the rays that failed a bitwise check; bit for bit on an
// Intel host with AVX-512). The triangle must still match.
inline size_t expect_batch_hits_match_single_ray_hits(const Accel& accel,
                                                      const std::vector<Ray>& rays,
                                                      RayCoherence coherence) {
  return expect_batch_hits_within(accel, rays, coherence, 1e-5f, 1e-4f);
}

// The rays (each spanning [0, inf)) as planes in arrays of exactly their count, so that a
// backend reading past the last ray reads outside them.
struct PlaneCopies {
  std::array<std::vector<float>, 6> component;
  RayPlanes planes;
  explicit PlaneCopies(const std::vector<Ray>& rays) {
    for (const Ray& r : rays)
      for (int k = 0; k < 3; ++k) {
        component[k].push_back(r.org[k]);
        component[3 + k].push_back(r.dir[k]);
      }
    for (int k = 0; k < 3; ++k) {
      planes.org[k] = component[k].data();
      planes.dir[k] = component[3 + k].data();
    }
    planes.size = rays.size();
  }
};

// intersect_planes must find bit for bit what intersect_batch finds on the same rays.
inline void expect_plane_hits_are_batch_hits(const Accel& accel, const std::vector<Ray>& rays,
                                             RayCoherence coherence) {
  const PlaneCopies copies(rays);
  std::vector<Hit> from_planes(rays.size()), from_records(rays.size());
  accel.intersect_planes(copies.planes, from_planes, coherence);
  accel.intersect_batch(rays, from_records, coherence);
  for (size_t i = 0; i < rays.size(); ++i) {
    SCOPED_TRACE("ray " + std::to_string(i));
    EXPECT_EQ(from_records[i].prim, from_planes[i].prim);
    EXPECT_EQ(from_records[i].t, from_planes[i].t);
    EXPECT_EQ(from_records[i].u, from_planes[i].u);
    EXPECT_EQ(from_records[i].v, from_planes[i].v);
  }
}

// Every ray of the batch must be blocked exactly when the single-ray call says so. Returns how
// many are blocked.
inline size_t expect_batch_occlusion_is_single_ray_occlusion(const Accel& accel,
                                                             const std::vector<Ray>& rays) {
  std::vector<uint8_t> blocked(rays.size(), 2);
  accel.occluded_batch(rays, blocked);
  size_t blocked_count = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const uint8_t single = accel.occluded(rays[i]) ? 1 : 0;
    EXPECT_EQ(single, blocked[i]) << "ray " << i;
    blocked_count += single;
  }
  return blocked_count;
}

}  // namespace tuneray::test
