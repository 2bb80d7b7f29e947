// quality=high: spatial splits duplicate references, yet every triangle is still found, and
// found once (a duplicated reference never yields a second, different answer).
#include <gtest/gtest.h>

#include "accel/tuned_bvh.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

TEST(SpatialSplits, EveryTriangleIsFound) {
  Mesh mesh = make_soup(10000, 31, 0.08f);
  for (const char* text : {"quality=medium", "quality=high", "quality=high,branching=8,compact=1",
                           "quality=high,branching=4,robust=1,max_leaf=1"}) {
    TunedBvhAccel accel(parse_bvh_config(text));
    accel.build(mesh.view());
    if (accel.config().quality == BvhQuality::kHigh) {
      ASSERT_GT(accel.tree_stats().references, mesh.triangles.size()) << "no split: " << text;
    }
    size_t missing = 0;
    for (uint32_t i = 0; i < mesh.triangles.size(); ++i) {
      const Triangle& t = mesh.triangles[i];
      Vec3f a = mesh.positions[t.v[0]], b = mesh.positions[t.v[1]], c = mesh.positions[t.v[2]];
      Vec3f n = normalize(cross(b - a, c - a));
      Vec3f centroid = (a + b + c) / 3.0f;
      Ray r{centroid + n * 1e-4f, 0, -n, 2e-4f};
      // Found: the closest hit is this triangle at t = 1e-4, or another triangle crossing the
      // soup even closer (the soup's triangles intersect each other).
      Hit h;
      const float at = 1e-4f * (1.0f + 1e-3f);
      if (!accel.intersect(r, h) || (h.prim != i && h.t > at)) ++missing;
      if (!accel.occluded(r)) ++missing;
    }
    EXPECT_EQ(missing, 0u) << text;
  }
}

}  // namespace
}  // namespace tuneray::test
