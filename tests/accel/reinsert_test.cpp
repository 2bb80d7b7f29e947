// reinsert=1: moving subtrees of the binary build lowers its SAH cost, keeps every leaf as it
// was, never makes the tree deeper than the limit, and rays find exactly what the tree as built
// finds.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "accel/bvh_build.h"
#include "accel/bvh_reinsert.h"
#include "accel/bvh_walk.h"
#include "accel/tuned_bvh.h"
#include "same_answers.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

struct Built {
  bvh::Tree tree;
  bvh::PrimitiveCache cache;
};

void build(const Mesh& mesh, const std::string& text, Built& out) {
  bvh::build_tree(mesh.view(), parse_bvh_config(text), *EmbreeDevice::shared(), out.cache,
                  out.tree);
}

// Small triangles with a few long ones among them: the binned builder's centroid splits leave
// the long ones stretching deep boxes, which reinsertion can move up.
Mesh soup_with_slivers(uint64_t seed) {
  Mesh mesh = make_soup(20000, seed);
  Pcg32 rng(seed + 1);
  for (int i = 0; i < 200; ++i) {
    const Vec3f a = random_point(rng, mesh.bounds());
    const Vec3f b = random_point(rng, mesh.bounds());
    mesh.add(a, b, a + Vec3f(0.01f, 0.0f, 0.01f));
  }
  return mesh;
}

TEST(Reinsert, LowersTheSahCostAsTheTreeWalkMeasuresIt) {
  const Mesh mesh = soup_with_slivers(5);
  // Compact nodes are quantized again when rewritten, which grows their boxes a little; spatial
  // splits leave the slivers little to gain.
  struct Case {
    const char* text;
    double tolerance, gain;
  };
  for (const Case& c : {Case{"branching=2", 1e-4, 0.95}, Case{"branching=2,compact=1", 1e-2, 0.95},
                        Case{"branching=2,quality=high", 1e-4, 0.99}}) {
    const char* text = c.text;
    SCOPED_TRACE(text);
    Built b;
    build(mesh, text, b);
    // With a zero intersection cost the walk's SAH is the summed inner area over the root's:
    // an independent computation of what reinsertion minimises.
    const bvh::TreeStats before = bvh::measure_tree(b.tree, 1.0, 0.0);
    const bvh::ReinsertStats stats = bvh::reinsert_subtrees(b.tree, bvh::kMaxTraversalDepth);
    const bvh::TreeStats after = bvh::measure_tree(b.tree, 1.0, 0.0);
    EXPECT_FALSE(stats.kept_original);
    EXPECT_NEAR(stats.cost_before, before.sah_cost, 1e-4 * before.sah_cost);
    EXPECT_NEAR(stats.cost_after, after.sah_cost, c.tolerance * after.sah_cost);
    EXPECT_LT(after.sah_cost, c.gain * before.sah_cost);
    EXPECT_GT(stats.moves, 0u);
    // The same leaves under as many inner nodes.
    EXPECT_EQ(after.leaf_count, before.leaf_count);
    EXPECT_EQ(after.references, before.references);
    EXPECT_EQ(after.node_count, before.node_count);
    EXPECT_EQ(after.leaf_code_mismatches, 0u);
    EXPECT_EQ(after.depth, stats.depth + 1);  // the walk counts the leaf level too
  }
}

TEST(Reinsert, NeverGoesDeeperThanTheLimit) {
  const Mesh mesh = soup_with_slivers(6);
  Built reference;
  build(mesh, "branching=2", reference);
  const int built_depth = bvh::measure_tree(reference.tree, 1.0, 1.0).depth - 1;
  for (int limit : {built_depth, built_depth + 2}) {
    Built b;
    build(mesh, "branching=2", b);
    const bvh::ReinsertStats stats = bvh::reinsert_subtrees(b.tree, limit);
    EXPECT_LE(stats.depth, limit);
    EXPECT_LE(bvh::measure_tree(b.tree, 1.0, 1.0).depth - 1, limit);
    EXPECT_LE(stats.cost_after, stats.cost_before);
  }
}

TEST(Reinsert, LeavesWiderTreesAndLoneLeavesAsBuilt) {
  const Mesh mesh = soup_with_slivers(7);
  Built wide;
  build(mesh, "branching=4", wide);
  const bvh::NodeRef root = wide.tree.root();
  EXPECT_TRUE(bvh::reinsert_subtrees(wide.tree, bvh::kMaxTraversalDepth).kept_original);
  EXPECT_EQ(wide.tree.root(), root);

  Mesh one;
  one.add(Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0));
  TunedBvhAccel accel(parse_bvh_config("branching=2,reinsert=1"));
  const BuildStats stats = accel.build(one.view());
  EXPECT_EQ(stats.leaf_count, 1u);
  Hit hit;
  ASSERT_TRUE(accel.intersect(Ray{Vec3f(0.2f, 0.2f, 1.0f), 0, Vec3f(0, 0, -1), kInf}, hit));
  EXPECT_EQ(hit.prim, 0u);
}

TEST(Reinsert, RaysFindExactlyWhatTheTreeAsBuiltFinds) {
  const Mesh mesh = soup_with_slivers(8);
  std::vector<Ray> rays;
  Pcg32 rng(9);
  for (int i = 0; i < 4000; ++i)
    rays.push_back(
        Ray{random_point(rng, mesh.bounds()), 0, random_direction(rng), 0.2f * rng.next_float()});
  for (const char* text :
       {"branching=2", "branching=2,collapse=0", "branching=2,sah_block_size=4,max_leaf=28",
        "branching=2,compact=1", "branching=2,robust=1", "branching=2,quality=high,static=1"}) {
    SCOPED_TRACE(text);
    TunedBvhAccel plain(parse_bvh_config(text));
    TunedBvhAccel moved(parse_bvh_config(std::string(text) + ",reinsert=1"));
    const BuildStats plain_stats = plain.build(mesh.view());
    const BuildStats stats = moved.build(mesh.view());
    EXPECT_NE(stats.notes.find("reinsertion"), std::string::npos) << stats.notes;
    EXPECT_EQ(moved.tree_stats().references, plain.tree_stats().references);
    EXPECT_NE(stats.sah_cost, plain_stats.sah_cost);
    const size_t hits = expect_same_answers(plain, moved, rays).hits;
    EXPECT_GT(hits, 0u);
    EXPECT_LT(hits, rays.size());
  }
}

}  // namespace
}  // namespace tuneray::test
