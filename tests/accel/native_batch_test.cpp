// Embree native's batches: a coherent batch goes through Embree's packet traversal, which must
// find exactly what the single-ray calls find, so the wavefront image stays the tile image.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "accel/embree_native.h"
#include "batch_check.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

// Camera-like rays in pixel order: one origin, directions over a grid that covers the sphere
// and the empty space around it.
std::vector<Ray> pixel_order_rays(int width, int height) {
  std::vector<Ray> rays;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Vec3f dir(-0.5f + (x + 0.5f) / width, -0.5f + (y + 0.5f) / height, 1.0f);
      rays.push_back(Ray{Vec3f(0.1f, 0.05f, -3.0f), 0, normalize(dir), kInf});
    }
  return rays;
}

TEST(NativeBatch, CoherentAndIncoherentBatchesFindTheSingleRayHitsBitForBit) {
  Mesh mesh = make_icosphere(4);
  EmbreeNativeAccel native;
  native.build(mesh.view());
  const std::vector<Ray> rays = pixel_order_rays(48, 40);
  size_t hit_count = 0;
  for (RayCoherence coherence : {RayCoherence::kCoherent, RayCoherence::kIncoherent})
    hit_count += expect_batch_hits_are_single_ray_hits(native, rays, coherence);
  // The grid must both hit and miss the sphere for the comparison to mean something.
  EXPECT_GT(hit_count, rays.size() / 4);
  EXPECT_LT(hit_count, 2 * rays.size());
}

// A batch whose length is no multiple of the packet width, as planes and as records, both
// coherences: the last packet's missing lanes must neither hit nor change the others.
TEST(NativeBatch, PlanesFindTheRecordsHitsAtEveryBatchLength) {
  Mesh mesh = make_icosphere(4);
  EmbreeNativeAccel native;
  native.build(mesh.view());
  const std::vector<Ray> all = pixel_order_rays(37, 29);
  for (size_t n : {size_t{1}, size_t{7}, size_t{8}, size_t{9}, all.size()}) {
    SCOPED_TRACE(std::to_string(n) + " rays");
    const std::vector<Ray> rays(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n));
    for (RayCoherence coherence : {RayCoherence::kCoherent, RayCoherence::kIncoherent}) {
      expect_plane_hits_are_batch_hits(native, rays, coherence);
      expect_batch_hits_are_single_ray_hits(native, rays, coherence);
    }
  }
}

// A ray whose segment ends before the sphere misses in a batch as it does alone: t stays at
// infinity, not at the segment's end.
TEST(NativeBatch, ARayEndingBeforeTheSurfaceMissesWithTheMissRecord) {
  Mesh mesh = make_icosphere(4);
  EmbreeNativeAccel native;
  native.build(mesh.view());
  std::vector<Ray> rays = pixel_order_rays(16, 16);
  for (size_t i = 0; i < rays.size(); i += 2) rays[i].tfar = 0.5f;  // the sphere is 2 away
  std::vector<Hit> hits(rays.size());
  native.intersect_batch(rays, hits, RayCoherence::kIncoherent);
  size_t hit_count = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    if (i % 2 == 0) {
      EXPECT_FALSE(hits[i].valid()) << "ray " << i;
      EXPECT_EQ(hits[i].t, kInf) << "ray " << i;
      EXPECT_EQ(hits[i].u, 0.0f) << "ray " << i;
    }
    hit_count += hits[i].valid() ? 1 : 0;
  }
  EXPECT_GT(hit_count, 0u);
  expect_batch_hits_are_single_ray_hits(native, rays, RayCoherence::kIncoherent);
}

}  // namespace
}  // namespace tuneray::test
