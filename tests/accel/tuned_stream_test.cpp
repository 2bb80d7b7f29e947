// The tuned BVH's stream traversal of shadow-ray batches (bvh_stream.cpp) against its single-ray
// any-hit kernel: every ray must get the same answer, whatever group it was traced in.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "accel/tuned_bvh.h"
#include "batch_check.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

// Shadow rays as the wavefront makes them: from points in and around the soup towards a few
// "lights", ending just short of them, in runs of neighbouring origins (so groups share their
// upper nodes) mixed with scattered ones (so every octant gets groups of all sizes, from one ray
// to more than a full stream).
std::vector<Ray> shadow_rays(size_t count, uint64_t seed) {
  Pcg32 rng(seed);
  const BBox around{Vec3f(-0.2f), Vec3f(1.2f)};
  const Vec3f lights[] = {Vec3f(0.5f, 1.4f, 0.5f), Vec3f(-0.3f, 0.2f, 0.9f),
                          Vec3f(0.5f, 0.5f, 0.5f)};
  std::vector<Ray> rays;
  Vec3f origin = random_point(rng, around);
  while (rays.size() < count) {
    if (rng.next_float() < 0.2f) origin = random_point(rng, around);
    const Vec3f o = origin + Vec3f(rng.next_float(), rng.next_float(), rng.next_float()) * 0.02f;
    const Vec3f to = lights[rng.next_u32() % 3] - o;
    const float dist = length(to);
    rays.push_back(Ray{o, 1e-4f, to / dist, dist * (1 - 1e-4f)});
  }
  return rays;
}

// Directions with zero and negative-zero components (each must land in the octant whose near
// planes its single-ray test uses), rays that end before they start, and rays of infinite range.
std::vector<Ray> awkward_rays() {
  std::vector<Ray> rays;
  const Vec3f o(0.5f, 0.5f, -0.5f);
  for (float zero : {0.0f, -0.0f}) {
    for (int i = 0; i < 5; ++i) {
      const float s = 0.1f * static_cast<float>(i);
      rays.push_back(Ray{o + Vec3f(s, 0, 0), 0, Vec3f(zero, zero, 1), kInf});
      rays.push_back(Ray{o + Vec3f(0, s, 0), 0, normalize(Vec3f(zero, 0.1f, 1)), 3.0f});
      rays.push_back(Ray{Vec3f(s, 0.5f, 0.5f), 0, Vec3f(1, zero, zero), kInf});
    }
  }
  rays.push_back(Ray{o, 2.0f, Vec3f(0, 0, 1), 1.0f});  // tnear > tfar: never blocked
  rays.push_back(Ray{o, 0, Vec3f(0, 0, 1), 0.0f});
  return rays;
}

TEST(TunedStream, ShadowBatchesGetTheSingleRayAnswers) {
  const Mesh mesh = make_soup(4000, 17, 0.06f);
  std::vector<Ray> rays = shadow_rays(3000, 23);
  const std::vector<Ray> awkward = awkward_rays();
  rays.insert(rays.end(), awkward.begin(), awkward.end());
  for (const char* text : kBatchKernelConfigs) {
    SCOPED_TRACE(text);
    TunedBvhAccel tuned(parse_bvh_config(text));
    tuned.build(mesh.view());
    const size_t blocked = expect_batch_occlusion_is_single_ray_occlusion(tuned, rays);
    // Both blocked and free rays, or the comparison means little.
    EXPECT_GT(blocked, rays.size() / 5);
    EXPECT_LT(blocked, rays.size() * 4 / 5);
  }
}

TEST(TunedStream, RayCountsAroundTheStreamSizeAndATreeThatIsOneLeaf) {
  const Mesh mesh = make_soup(4000, 29, 0.06f);
  Mesh one_triangle;
  one_triangle.add(Vec3f(0, 0, 0.5f), Vec3f(1, 0, 0.5f), Vec3f(0, 1, 0.5f));
  const std::vector<Ray> all = shadow_rays(1100, 31);
  for (const Mesh* m : {&mesh, static_cast<const Mesh*>(&one_triangle)}) {
    TunedBvhAccel tuned(parse_bvh_config("branching=8,sah_block_size=4,min_leaf=4,max_leaf=28"));
    tuned.build(m->view());
    for (size_t n : {0, 1, 2, 3, 31, 32, 33, 63, 64, 65, 127, 128, 129, 200, 520, 1100}) {
      SCOPED_TRACE(n);
      expect_batch_occlusion_is_single_ray_occlusion(
          tuned, std::vector<Ray>(all.begin(), all.begin() + static_cast<long>(n)));
    }
  }
}

TEST(TunedStream, ARayWithANanDirectionLeadingItsGroupChangesNoOtherAnswer) {
  const Mesh mesh = make_soup(4000, 37, 0.06f);
  // A NaN x component has a clear sign bit, so the ray joins the rays going towards +x; first in
  // the batch, it leads their group. It enters no box and is never blocked.
  std::vector<Ray> rays = {
      Ray{Vec3f(0.5f), 0, Vec3f(std::numeric_limits<float>::quiet_NaN(), 0.1f, 1), kInf}};
  Pcg32 rng(41);
  for (int i = 0; i < 40; ++i) {
    const Vec3f o(0.3f + 0.4f * rng.next_float(), 0.3f + 0.4f * rng.next_float(), -0.5f);
    rays.push_back(Ray{o, 0, normalize(Vec3f(0.1f, 0.1f, 1)), kInf});
  }
  TunedBvhAccel tuned(parse_bvh_config("branching=8,sah_block_size=4,min_leaf=4,max_leaf=28"));
  tuned.build(mesh.view());
  EXPECT_GT(expect_batch_occlusion_is_single_ray_occlusion(tuned, rays), 20u);
}

}  // namespace
}  // namespace tuneray::test
