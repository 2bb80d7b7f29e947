// The two instruction-set copies of the single-ray kernels (bvh_traverse.cpp: AVX2, and AVX-512
// where the CPU has it) are one source compiled twice: every ray must get the same answer bit for
// bit from either, for every width, layout and triangle test, so a render does not depend on
// which copy its CPU runs.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

#include "accel/bvh_traverse.h"
#include "accel/kernel_isa.h"
#include "accel/tuned_bvh.h"
#include "kernel_isa_cap.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

struct Answers {
  std::vector<Hit> hits;
  std::vector<bool> blocked;
};

// Builds the tree with the kernels of `isa` and traces every ray alone (closest and any hit).
Answers trace_with(const char* isa, const Mesh& mesh, const BvhConfig& config,
                   const std::vector<Ray>& rays) {
  const KernelIsaCap cap(isa);
  TunedBvhAccel tuned(config);
  tuned.build(mesh.view());
  Answers a;
  for (const Ray& ray : rays) {
    Hit h;
    tuned.intersect(ray, h);
    a.hits.push_back(h);
    a.blocked.push_back(tuned.occluded(ray));
  }
  return a;
}

TEST(SingleRayCopies, TheCapSelectsAnotherCopy) {
  if (!bvh::cpu_has_avx512()) GTEST_SKIP() << "this CPU has no AVX-512";
  const bvh::TreeShape shape{8, false, false};
  bvh::Kernels wide, narrow;
  {
    const KernelIsaCap cap("avx512");
    wide = bvh::select_kernels(shape);
  }
  {
    const KernelIsaCap cap("avx2");
    narrow = bvh::select_kernels(shape);
  }
  EXPECT_NE(wide.intersect, narrow.intersect);
  EXPECT_NE(wide.occluded, narrow.occluded);
}

TEST(SingleRayCopies, Avx512AndAvx2FindTheSameHitsBitForBit) {
  if (!bvh::cpu_has_avx512()) GTEST_SKIP() << "this CPU has no AVX-512";
  const Mesh mesh = make_soup(3000, 17);
  Pcg32 rng(5);
  const BBox box = mesh.bounds();
  std::vector<Ray> rays;
  for (int i = 0; i < 4000; ++i) {
    // Half of the rays end inside the soup, so any-hit queries find both answers.
    const float tfar = i % 2 ? kInf : 0.3f;
    rays.push_back(Ray{random_point(rng, box), 0, random_direction(rng), tfar});
  }
  for (const char* text :
       {"branching=2,collapse=0", "branching=4,collapse=0", "branching=8", "branching=8,compact=1",
        "branching=8,robust=1", "branching=2,compact=1,robust=1,collapse=0",
        "branching=2,min_leaf=4,max_leaf=28,sah_block_size=4,static=1,reinsert=1,"
        "optimal_collapse=1"}) {
    SCOPED_TRACE(text);
    const BvhConfig config = parse_bvh_config(text);
    const Answers wide = trace_with("avx512", mesh, config, rays);
    const Answers narrow = trace_with("avx2", mesh, config, rays);
    size_t hits = 0, blocked = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      SCOPED_TRACE(i);
      const Hit& a = wide.hits[i];
      const Hit& b = narrow.hits[i];
      ASSERT_EQ(a.prim, b.prim);
      ASSERT_EQ(std::bit_cast<uint32_t>(a.t), std::bit_cast<uint32_t>(b.t));
      ASSERT_EQ(std::bit_cast<uint32_t>(a.u), std::bit_cast<uint32_t>(b.u));
      ASSERT_EQ(std::bit_cast<uint32_t>(a.v), std::bit_cast<uint32_t>(b.v));
      ASSERT_EQ(wide.blocked[i], narrow.blocked[i]);
      hits += a.valid();
      blocked += wide.blocked[i];
    }
    // Both answers occur, or the comparison means little.
    EXPECT_GT(hits, rays.size() / 10);
    EXPECT_LT(hits, rays.size());
    EXPECT_GT(blocked, rays.size() / 10);
    EXPECT_LT(blocked, rays.size());
  }
}

}  // namespace
}  // namespace tuneray::test
