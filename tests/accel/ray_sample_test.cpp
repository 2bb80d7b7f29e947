// ray_weight: a view's sampled rays price the boxes of the reinsertion and the SAH-optimal
// collapse. The share of segments through a box agrees with an independent slab test in double
// precision; the measure is the surface area when unweighted and the stated blend otherwise; a
// weighted tree finds exactly the hits of the unweighted one; without a sample nothing changes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "accel/bvh_build.h"
#include "accel/bvh_reinsert.h"
#include "accel/ray_sample.h"
#include "accel/tuned_bvh.h"
#include "same_answers.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

// Whether the segment [0, length] of (org, dir) meets `box`, in double precision, axis by axis
// (a zero direction component: inside the slab or not at all).
bool crosses(const Vec3f& org, const Vec3f& dir, double length, const BBox& box) {
  double enter = 0.0, leave = length;
  const float o[3] = {org.x, org.y, org.z}, d[3] = {dir.x, dir.y, dir.z};
  const float lo[3] = {box.lo.x, box.lo.y, box.lo.z}, hi[3] = {box.hi.x, box.hi.y, box.hi.z};
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0f) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double t0 = (lo[a] - static_cast<double>(o[a])) / d[a];
    double t1 = (hi[a] - static_cast<double>(o[a])) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
  }
  return enter <= leave;
}

BBox box_of(Vec3f lo, Vec3f hi) {
  BBox b;
  b.extend(lo);
  b.extend(hi);
  return b;
}

TEST(RaySample, VisitShareAgreesWithADoublePrecisionSlabTest) {
  Pcg32 rng(11);
  const BBox space = box_of(Vec3f(-1), Vec3f(2));
  struct Segment {
    Vec3f org, dir;
    float length;
  };
  std::vector<Segment> segments;
  bvh::RaySample sample;
  for (int i = 0; i < 1003; ++i) {  // not a whole number of groups of eight
    Segment s{random_point(rng, space), random_direction(rng), 3.0f * rng.next_float()};
    if (i % 50 == 0) s.dir = Vec3f(0.0f, 0.0f, i % 100 == 0 ? 1.0f : -1.0f);  // axis-parallel
    segments.push_back(s);
    sample.add(Ray{s.org, 0, s.dir, kInf}, s.length);
  }
  ASSERT_EQ(sample.size(), segments.size());
  size_t compared = 0;
  for (int k = 0; k < 200; ++k) {
    const Vec3f a = random_point(rng, space), b = random_point(rng, space);
    const BBox box = box_of(a, b);
    size_t expected = 0;
    for (const Segment& s : segments) expected += crosses(s.org, s.dir, s.length, box) ? 1 : 0;
    // Float and double slab distances may disagree on a segment that grazes an edge.
    EXPECT_NEAR(sample.visit_share(box) * static_cast<float>(segments.size()),
                static_cast<float>(expected), 2.0f);
    compared += expected;
  }
  EXPECT_GT(compared, 1000u);  // the boxes were crossed, not all missed
}

TEST(RaySample, CountsSegmentsNotLines) {
  bvh::RaySample sample;
  // Four rays along +x from x = 0 at y = 0.5, z = 0.5; they end at x = 1, 2, 3 and 4.
  for (int i = 1; i <= 4; ++i)
    sample.add(Ray{Vec3f(0.0f, 0.5f, 0.5f), 0, Vec3f(1, 0, 0), kInf}, static_cast<float>(i));
  EXPECT_FLOAT_EQ(sample.visit_share(box_of(Vec3f(0.5f, 0, 0), Vec3f(0.9f, 1, 1))), 1.0f);
  EXPECT_FLOAT_EQ(sample.visit_share(box_of(Vec3f(2.5f, 0, 0), Vec3f(2.9f, 1, 1))), 0.5f);
  EXPECT_FLOAT_EQ(sample.visit_share(box_of(Vec3f(5.0f, 0, 0), Vec3f(6.0f, 1, 1))), 0.0f);
  // Behind the origins, and beside the rays' line.
  EXPECT_FLOAT_EQ(sample.visit_share(box_of(Vec3f(-2.0f, 0, 0), Vec3f(-1.0f, 1, 1))), 0.0f);
  EXPECT_FLOAT_EQ(sample.visit_share(box_of(Vec3f(0.5f, 2, 0), Vec3f(0.9f, 3, 1))), 0.0f);
  // A ray's own tfar shortens its segment.
  sample.add(Ray{Vec3f(0.0f, 0.5f, 0.5f), 0, Vec3f(1, 0, 0), 0.25f}, 10.0f);
  EXPECT_FLOAT_EQ(sample.visit_share(box_of(Vec3f(0.5f, 0, 0), Vec3f(0.9f, 1, 1))), 0.8f);
  EXPECT_FLOAT_EQ(sample.visit_share(BBox{}), 0.0f);  // an empty box
}

TEST(RaySample, SkipsSegmentsThatAreNotNumbers) {
  bvh::RaySample sample;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float infinity = std::numeric_limits<float>::infinity();
  sample.add(Ray{Vec3f(nan, 0, 0), 0, Vec3f(1, 0, 0), kInf}, 1.0f);
  sample.add(Ray{Vec3f(0), 0, Vec3f(0, infinity, 0), kInf}, 1.0f);
  sample.add(Ray{Vec3f(0), 0, Vec3f(0), kInf}, 1.0f);
  sample.add(Ray{Vec3f(0), 0, Vec3f(1, 0, 0), kInf}, -1.0f);
  sample.add(Ray{Vec3f(0), 0, Vec3f(1, 0, 0), kInf}, nan);
  sample.add(Ray{Vec3f(0), 0, Vec3f(1, 0, 0), infinity}, infinity);
  EXPECT_TRUE(sample.empty());
  EXPECT_FLOAT_EQ(sample.visit_share(box_of(Vec3f(-1), Vec3f(1))), 0.0f);
  // An unbounded length is the ray's own tfar (kInf, the renderer's "no hit", is a number).
  sample.add(Ray{Vec3f(0), 0, Vec3f(1, 0, 0), kInf}, infinity);
  EXPECT_EQ(sample.size(), 1u);
  EXPECT_FLOAT_EQ(sample.visit_share(box_of(Vec3f(1e20f, -1, -1), Vec3f(2e20f, 1, 1))), 1.0f);
}

TEST(BoxMeasure, IsTheAreaUnweightedAndTheStatedBlendWeighted) {
  const BBox scene = box_of(Vec3f(0), Vec3f(2));  // area 24
  const BBox box = box_of(Vec3f(0), Vec3f(1));    // area 6
  EXPECT_FLOAT_EQ(bvh::BoxMeasure()(box), 6.0f);
  bvh::RaySample sample;
  sample.add(Ray{Vec3f(0.5f, 0.5f, -1.0f), 0, Vec3f(0, 0, 1), kInf}, 10.0f);  // through box
  sample.add(Ray{Vec3f(1.5f, 1.5f, -1.0f), 0, Vec3f(0, 0, 1), kInf}, 10.0f);  // beside it
  const bvh::BoxMeasure weighted(&sample, 0.75f, scene);
  EXPECT_TRUE(weighted.weighted());
  EXPECT_FLOAT_EQ(weighted(box), 0.25f * 6.0f / 24.0f + 0.75f * 0.5f);
  // No sample, an empty one or a zero weight: the plain area.
  const bvh::RaySample empty;
  for (const bvh::BoxMeasure& plain :
       {bvh::BoxMeasure(nullptr, 0.5f, scene), bvh::BoxMeasure(&empty, 0.5f, scene),
        bvh::BoxMeasure(&sample, 0.0f, scene)}) {
    EXPECT_FALSE(plain.weighted());
    EXPECT_FLOAT_EQ(plain(box), 6.0f);
  }
}

// Camera-like rays: from one point in front of the soup, into a narrow cone, ending where the
// soup's tree says they hit (or past it).
std::shared_ptr<bvh::RaySample> view_sample(const Accel& accel, const Mesh& mesh, int count) {
  auto sample = std::make_shared<bvh::RaySample>();
  Pcg32 rng(21);
  const Vec3f eye(0.5f, 0.5f, -1.0f);
  for (int i = 0; i < count; ++i) {
    const Vec3f target(0.3f + 0.2f * rng.next_float(), 0.3f + 0.2f * rng.next_float(), 0.5f);
    Ray ray{eye, 0, normalize(target - eye), kInf};
    Hit hit;
    sample->add(ray, accel.intersect(ray, hit) ? hit.t : 2.0f * mesh.bounds().diagonal());
  }
  return sample;
}

TEST(RayWeight, LowersItsOwnCostAndFindsExactlyTheHitsOfTheUnweightedTree) {
  const Mesh mesh = make_soup(20000, 31);
  const std::string text = "branching=2,sah_block_size=4,min_leaf=4,max_leaf=28,optimal_collapse=1";
  TunedBvhAccel plain(parse_bvh_config(text + ",reinsert=1"));
  plain.build(mesh.view());
  const auto sample = view_sample(plain, mesh, 512);

  // The reinsertion alone, on the measure: it lowers the weighted cost it reports.
  bvh::Tree tree;
  bvh::PrimitiveCache cache;
  bvh::build_tree(mesh.view(), parse_bvh_config("branching=2"), *EmbreeDevice::shared(), cache,
                  tree);
  const bvh::ReinsertStats stats = bvh::reinsert_subtrees(
      tree, bvh::kMaxTraversalDepth, bvh::BoxMeasure(sample.get(), 0.5f, mesh.bounds()));
  EXPECT_TRUE(stats.weighted);
  EXPECT_FALSE(stats.kept_original);
  EXPECT_LT(stats.cost_after, stats.cost_before);

  std::vector<Ray> rays;
  Pcg32 rng(22);
  for (int i = 0; i < 3000; ++i)
    rays.push_back(
        Ray{random_point(rng, mesh.bounds()), 0, random_direction(rng), 0.3f * rng.next_float()});
  for (const char* extra : {",reinsert=1", ",reinsert=0", ",reinsert=1,static=1"}) {
    SCOPED_TRACE(extra);
    TunedBvhAccel reference(parse_bvh_config(text + extra));
    TunedBvhAccel weighted(parse_bvh_config(text + extra + ",ray_weight=0.5"));
    weighted.set_ray_sample(sample);
    reference.build(mesh.view());
    const BuildStats built = weighted.build(mesh.view());
    EXPECT_NE(built.notes.find("sampled rays of the view"), std::string::npos) << built.notes;
    EXPECT_EQ(weighted.tree_stats().references, reference.tree_stats().references);
    const AnswerCounts counts = expect_same_answers(reference, weighted, rays);
    EXPECT_GT(counts.hits, 0u);
    EXPECT_LT(counts.hits, rays.size());
  }
}

TEST(RayWeight, WithoutASampleTheTreeIsTheUnweightedOne) {
  const Mesh mesh = make_soup(5000, 41);
  const std::string text = "branching=2,sah_block_size=4,max_leaf=28,optimal_collapse=1,reinsert=1";
  TunedBvhAccel reference(parse_bvh_config(text));
  TunedBvhAccel weighted(parse_bvh_config(text + ",ray_weight=0.7"));
  const BuildStats a = reference.build(mesh.view());
  const BuildStats b = weighted.build(mesh.view());
  EXPECT_EQ(a.sah_cost, b.sah_cost);
  EXPECT_EQ(a.node_count, b.node_count);
  EXPECT_EQ(a.leaf_count, b.leaf_count);
  EXPECT_NE(b.notes.find("without a ray sample"), std::string::npos) << b.notes;
}

TEST(RayWeight, ParsesPrintsAndRejects) {
  const BvhConfig c = parse_bvh_config("ray_weight=0.25");
  EXPECT_FLOAT_EQ(c.ray_weight, 0.25f);
  EXPECT_NE(c.to_string().find(",ray_weight=0.25"), std::string::npos);
  EXPECT_EQ(parse_bvh_config(c.to_string()), c);
  // Unset, it is not printed: configurations stored before it existed keep their text.
  EXPECT_EQ(BvhConfig{}.to_string().find("ray_weight"), std::string::npos);
  for (const char* bad : {"ray_weight=1.5", "ray_weight=-0.1", "ray_weight=x"})
    EXPECT_THROW(parse_bvh_config(bad), std::invalid_argument) << bad;
}

}  // namespace
}  // namespace tuneray::test
