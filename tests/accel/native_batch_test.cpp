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

}  // namespace
}  // namespace tuneray::test
