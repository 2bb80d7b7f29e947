// Every one of the 11 parameters changes the built tree where it should (node count, depth,
// leaf sizes, memory or SAH cost), and a refused build is a clean failure.
#include <gtest/gtest.h>

#include "accel/tuned_bvh.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

class Parameters : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { mesh_ = new Mesh(make_soup(20000, 21)); }
  static void TearDownTestSuite() { delete mesh_; }

  struct Built {
    BuildStats stats;
    bvh::TreeStats tree;
  };
  // The tree as Embree's builder shapes it: collapse (its own tests, collapse_test.cpp) would
  // give every branching factor 8-wide nodes.
  static Built build(const std::string& text) {
    TunedBvhAccel accel(parse_bvh_config(text.empty() ? "collapse=0" : text + ",collapse=0"));
    BuildStats stats = accel.build(mesh_->view());
    return {stats, accel.tree_stats()};
  }
  static Mesh* mesh_;
};
Mesh* Parameters::mesh_ = nullptr;

TEST_F(Parameters, QualityChangesSahCostAndReferences) {
  Built low = build("quality=low"), medium = build("quality=medium"), high = build("quality=high");
  EXPECT_GT(low.stats.sah_cost, medium.stats.sah_cost * 1.02);
  EXPECT_LT(high.stats.sah_cost, medium.stats.sah_cost);
  EXPECT_EQ(medium.tree.references, mesh_->triangles.size());
  EXPECT_GT(high.tree.references, mesh_->triangles.size());  // spatial splits duplicated some
  EXPECT_NE(high.stats.notes.find("spatial splits"), std::string::npos);
}

TEST_F(Parameters, BranchingChangesNodeCountAndDepth) {
  Built b2 = build("branching=2"), b4 = build("branching=4"), b8 = build("branching=8");
  EXPECT_GT(b2.stats.node_count, b4.stats.node_count);
  EXPECT_GT(b4.stats.node_count, b8.stats.node_count);
  EXPECT_GT(b2.stats.depth, b8.stats.depth);
}

TEST_F(Parameters, MaxDepthBoundsDepthAndTooSmallIsRefused) {
  Built deep = build("branching=2,max_depth=64,max_leaf=1");
  Built capped = build("branching=2,max_depth=24,max_leaf=1");
  EXPECT_LE(capped.stats.depth, 24 + 1);
  EXPECT_NE(deep.stats.sah_cost, capped.stats.sah_cost);

  TunedBvhAccel accel(parse_bvh_config("branching=2,max_depth=8"));
  EXPECT_THROW(accel.build(mesh_->view()), BuildError);
  // The accelerator is left empty and usable.
  Hit h;
  EXPECT_FALSE(accel.intersect(Ray{Vec3f(0.5f), 0, Vec3f(0, 0, 1), kInf}, h));
  accel.set_config(parse_bvh_config("branching=2,max_depth=32"));
  accel.build(mesh_->view());
  EXPECT_GT(accel.tree_stats().node_count, 0u);
}

TEST_F(Parameters, SahBlockSizeChangesTheTree) {
  Built b1 = build("branching=4,sah_block_size=1"), b16 = build("branching=4,sah_block_size=16");
  EXPECT_NE(b1.stats.leaf_count, b16.stats.leaf_count);
  EXPECT_NE(b1.stats.sah_cost, b16.stats.sah_cost);
}

// The traversal takes a fast leaf's pack count from its reference: every leaf of every width,
// quality and leaf size (up to 8 packs at max_leaf=32), and after the static relayout, must carry
// the count of its header.
TEST_F(Parameters, LeafReferencesCarryThePackCount) {
  for (const char* text : {"branching=2", "branching=4,max_leaf=32,min_leaf=8,sah_block_size=16",
                           "branching=8,max_leaf=5", "branching=8,quality=high,max_leaf=8",
                           "branching=8,quality=low,min_leaf=8", "branching=8,static=1,max_leaf=16",
                           "branching=4,robust=1,max_leaf=7"}) {
    Built b = build(text);
    EXPECT_GT(b.tree.leaf_count, 0u) << text;
    EXPECT_EQ(b.tree.leaf_code_mismatches, 0u) << text;
  }
}

TEST_F(Parameters, MinLeafMakesLeavesLarger) {
  Built m1 = build("min_leaf=1"), m8 = build("min_leaf=8");
  EXPECT_LT(m8.stats.leaf_count, m1.stats.leaf_count);
  // Morton uses min_leaf as its leaf size, up to max_leaf.
  Built low1 = build("quality=low,min_leaf=1"), low8 = build("quality=low,min_leaf=8");
  EXPECT_LT(low8.stats.leaf_count * 3, low1.stats.leaf_count);
  Built low24 = build("quality=low,min_leaf=24");
  EXPECT_LT(low24.stats.leaf_count * 2, low8.stats.leaf_count);
  EXPECT_GT(low24.tree.max_leaf_size, 8u);
  EXPECT_LE(low24.tree.max_leaf_size, 24u);
}

TEST_F(Parameters, MaxLeafBoundsLeafSize) {
  Built small = build("max_leaf=2"), large = build("max_leaf=32,cost_ratio=20");
  EXPECT_LE(small.tree.max_leaf_size, 2u);
  EXPECT_GT(large.tree.max_leaf_size, 2u);
  EXPECT_LE(large.tree.max_leaf_size, 32u);
}

// Embree's Morton builder splits at Morton bits down to 8 levels above max_depth and cuts what is
// left there into balanced subtrees with leaves of up to max_leaf primitives; a deep limit leaves
// no such subtrees, and max_leaf then changes nothing.
TEST_F(Parameters, MortonUsesMaxLeafOnlyNearTheDepthLimit) {
  Built small = build("quality=low,branching=2,max_depth=16,max_leaf=4");
  Built large = build("quality=low,branching=2,max_depth=16,max_leaf=32");
  EXPECT_LE(small.tree.max_leaf_size, 4u);
  EXPECT_GT(large.tree.max_leaf_size, 4u);
  EXPECT_LE(large.tree.max_leaf_size, 32u);
  EXPECT_GT(small.stats.leaf_count, large.stats.leaf_count * 3);
  Built deep_small = build("quality=low,branching=2,max_depth=64,max_leaf=4");
  Built deep_large = build("quality=low,branching=2,max_depth=64,max_leaf=32");
  EXPECT_EQ(deep_small.stats.leaf_count, deep_large.stats.leaf_count);
  EXPECT_EQ(deep_small.stats.sah_cost, deep_large.stats.sah_cost);
  EXPECT_LE(deep_large.tree.max_leaf_size, 1u);  // min_leaf, the Morton leaf size
}

TEST_F(Parameters, OnlyTheCostRatioMatters) {
  Built r1 = build("trav_cost=1,int_cost=1"), r2 = build("trav_cost=2,int_cost=2");
  EXPECT_EQ(r1.stats.node_count, r2.stats.node_count);
  EXPECT_EQ(r1.stats.leaf_count, r2.stats.leaf_count);
  Built cheap_nodes = build("cost_ratio=0.05"), dear_nodes = build("cost_ratio=20");
  EXPECT_GT(cheap_nodes.stats.leaf_count, dear_nodes.stats.leaf_count);
}

TEST_F(Parameters, StaticRelaysTheSameTreeOut) {
  Built as_built = build("branching=4"), relaid = build("branching=4,static=1");
  EXPECT_EQ(as_built.stats.node_count, relaid.stats.node_count);
  EXPECT_EQ(as_built.stats.memory_bytes, relaid.stats.memory_bytes);
  EXPECT_DOUBLE_EQ(as_built.stats.sah_cost, relaid.stats.sah_cost);
  EXPECT_NE(relaid.stats.notes.find("relaid out"), std::string::npos);
  EXPECT_EQ(as_built.stats.notes.find("relaid out"), std::string::npos);
}

TEST_F(Parameters, CompactUsesLessMemory) {
  for (int width : {2, 4, 8}) {
    std::string w = "branching=" + std::to_string(width);
    Built fast = build(w), compact = build(w + ",compact=1");
    EXPECT_EQ(fast.stats.node_count, compact.stats.node_count);
    EXPECT_LT(compact.stats.memory_bytes * 2, fast.stats.memory_bytes) << w;
    // Quantized boxes are conservative, so they can only grow the SAH cost.
    EXPECT_GE(compact.stats.sah_cost, fast.stats.sah_cost * 0.999) << w;
  }
}

TEST_F(Parameters, RobustKeepsTheTreeAndLayoutSize) {
  Built fast = build("branching=8"), robust = build("branching=8,robust=1");
  EXPECT_EQ(fast.stats.node_count, robust.stats.node_count);
  EXPECT_EQ(fast.stats.memory_bytes, robust.stats.memory_bytes);
  EXPECT_EQ(robust.stats.notes.find("fell back"), std::string::npos);
}

}  // namespace
}  // namespace tuneray::test
