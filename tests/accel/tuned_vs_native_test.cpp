// The tuned BVH against Embree's native BVH on procedural geometry: same hit/miss, distance
// (1e-5 relative) and triangle (except true ties) for closest-hit and shadow rays.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "accel/embree_native.h"
#include "accel/tuned_bvh.h"
#include "compare_backends.h"
#include "sampled_configs.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

constexpr size_t kRaysPerKind = 20000;

void expect_agreement(const Mesh& mesh, uint64_t seed) {
  GeometryView g = mesh.view();
  EmbreeNativeAccel native;
  native.build(g);
  RaySets rays = make_ray_sets(g, kRaysPerKind, seed);
  for (const std::string& text : sampled_configs()) {
    TunedBvhAccel tuned(parse_bvh_config(text));
    tuned.build(g);
    Agreement a = compare(tuned, native, rays, g);
    SCOPED_TRACE("config '" + text + "': " + a.summary());
    EXPECT_GT(a.hits, kRaysPerKind / 10);
    // Rays grazing an edge may be decided differently by two non-watertight tests: allow one in
    // 20,000, nothing systematic.
    EXPECT_LE(a.hit_mismatch, a.rays / 20000);
    EXPECT_LE(a.shadow_mismatch, a.rays / 20000);
    EXPECT_EQ(a.dist_mismatch, 0u);
    EXPECT_EQ(a.prim_mismatch, 0u);
  }
}

TEST(TunedVsNative, TriangleSoup) {
  expect_agreement(make_soup(20000, 1), 11);
}

TEST(TunedVsNative, Icosphere) {
  expect_agreement(make_icosphere(5), 12);
}

TEST(TunedVsNative, GridBoxAxisAlignedTies) {
  expect_agreement(make_grid_box(40), 13);
}

TEST(TunedVsNative, TwoSpheresAndSoup) {
  Mesh m = make_icosphere(4, Vec3f(0.5f));
  Mesh s = make_soup(5000, 7);
  for (const Triangle& t : s.triangles) {
    uint32_t base = static_cast<uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(),
                       {s.positions[t.v[0]], s.positions[t.v[1]], s.positions[t.v[2]]});
    m.triangles.push_back({{base, base + 1, base + 2}});
  }
  expect_agreement(m, 14);
}

TEST(TunedBvh, BatchMatchesSingleRays) {
  Mesh mesh = make_soup(5000, 3);
  GeometryView g = mesh.view();
  TunedBvhAccel tuned(parse_bvh_config("branching=8"));
  tuned.build(g);
  RaySets rays = make_ray_sets(g, 2000, 5);
  std::vector<Hit> hits(rays.closest.size());
  tuned.intersect_batch(rays.closest, hits);
  std::vector<uint8_t> blocked(rays.shadow.size());
  tuned.occluded_batch(rays.shadow, blocked);
  for (size_t i = 0; i < rays.closest.size(); ++i) {
    Hit h;
    tuned.intersect(rays.closest[i], h);
    EXPECT_EQ(h.prim, hits[i].prim);
    EXPECT_EQ(h.t, hits[i].t);
  }
  for (size_t i = 0; i < rays.shadow.size(); ++i)
    EXPECT_EQ(tuned.occluded(rays.shadow[i]) ? 1 : 0, blocked[i]);
}

TEST(TunedBvh, EmptyGeometryMissesEverything) {
  Mesh mesh;
  TunedBvhAccel tuned;
  BuildStats stats = tuned.build(mesh.view());
  EXPECT_EQ(stats.node_count, 0u);
  Hit h;
  EXPECT_FALSE(tuned.intersect(Ray{Vec3f(0), 0, Vec3f(0, 0, 1), kInf}, h));
  EXPECT_FALSE(tuned.occluded(Ray{Vec3f(0), 0, Vec3f(0, 0, 1), kInf}));
}

TEST(TunedBvh, SingleTriangleIsARootLeaf) {
  Mesh mesh;
  mesh.add(Vec3f(-1, -1, 2), Vec3f(1, -1, 2), Vec3f(0, 1, 2));
  for (const char* text : {"branching=2", "branching=8,compact=1", "robust=1"}) {
    TunedBvhAccel tuned(parse_bvh_config(text));
    tuned.build(mesh.view());
    Hit h;
    ASSERT_TRUE(tuned.intersect(Ray{Vec3f(0), 0, Vec3f(0, 0, 1), kInf}, h)) << text;
    EXPECT_FLOAT_EQ(h.t, 2.0f);
    EXPECT_EQ(h.prim, 0u);
    // (0,0,2) = 0.25 a + 0.25 b + 0.5 c
    EXPECT_NEAR(h.u, 0.25f, 1e-6f);
    EXPECT_NEAR(h.v, 0.5f, 1e-6f);
    EXPECT_FALSE(tuned.occluded(Ray{Vec3f(0), 0, Vec3f(0, 0, 1), 1.9f}));
    EXPECT_TRUE(tuned.occluded(Ray{Vec3f(0), 0, Vec3f(0, 0, 1), 2.1f}));
  }
}

// The tuned box test orders floats by their bits, which is exact only from a non-negative start,
// so a ray's start is clamped to 0 (Embree asks tnear >= 0, and the native backend clamps too): a
// negative or NaN tnear finds what a ray from its origin finds, never the triangle behind the
// origin, in single rays and batches.
void expect_starts_count_from_the_origin(const Accel& accel, const std::string& name) {
  for (float tnear : {-5.0f, -0.0f, std::numeric_limits<float>::quiet_NaN()}) {
    SCOPED_TRACE(name + ", tnear " + std::to_string(tnear));
    Hit h;
    ASSERT_TRUE(accel.intersect(Ray{Vec3f(0), tnear, Vec3f(0, 0, 1), kInf}, h));
    EXPECT_FLOAT_EQ(h.t, 2.0f);
    EXPECT_EQ(h.prim, 1u);
    EXPECT_FALSE(accel.occluded(Ray{Vec3f(0, 0, 1), tnear, Vec3f(0, 0, -1), 2.9f}));
    EXPECT_TRUE(accel.occluded(Ray{Vec3f(0, 0, 1), tnear, Vec3f(0, 0, -1), 3.1f}));
    // A batch of one octant: coherent, it goes through the packet kernels where the tree has them.
    std::vector<Ray> rays;
    for (int i = 0; i < 64; ++i)
      rays.push_back(
          Ray{Vec3f(0.01f * static_cast<float>(i % 8), 0.01f * static_cast<float>(i / 8), 0), tnear,
              Vec3f(0.001f, 0.001f, 1), kInf});
    for (RayCoherence coherence : {RayCoherence::kCoherent, RayCoherence::kIncoherent}) {
      std::vector<Hit> hits(rays.size());
      accel.intersect_batch(rays, hits, coherence);
      for (const Hit& b : hits) EXPECT_EQ(b.prim, 1u);
    }
    // Shadow rays of the same batch towards the triangle behind them, which they must not see.
    for (Ray& r : rays) r.tfar = 1.9f;
    std::vector<uint8_t> blocked(rays.size(), 1);
    accel.occluded_batch(rays, blocked);
    for (uint8_t b : blocked) EXPECT_EQ(b, 0);
  }
}

TEST(TunedBvh, NegativeOrNanStartsCountFromTheOrigin) {
  Mesh mesh;
  mesh.add(Vec3f(-1, -1, -2), Vec3f(1, -1, -2), Vec3f(0, 1, -2));  // behind the rays
  mesh.add(Vec3f(-1, -1, 2), Vec3f(1, -1, 2), Vec3f(0, 1, 2));
  for (const char* text : {"branching=2", "branching=8", "branching=8,compact=1", "robust=1"}) {
    TunedBvhAccel tuned(parse_bvh_config(text));
    tuned.build(mesh.view());
    expect_starts_count_from_the_origin(tuned, text);
  }
  EmbreeNativeAccel native;
  native.build(mesh.view());
  expect_starts_count_from_the_origin(native, "native");
}

}  // namespace
}  // namespace tuneray::test
