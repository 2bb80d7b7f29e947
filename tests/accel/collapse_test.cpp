// collapse=1: the 8-wide tree made from a 2- or 4-wide build holds the same leaves (or, with
// leaves priced in packs, fewer holding the same references), its nodes are as full as the
// greedy rule allows (where that rule collapses it), its boxes still contain what lies below
// them, and rays find exactly what the uncollapsed tree finds; all of it greedily and by the
// SAH-optimal plan, whose tree costs what the plan says and never more than the greedy one.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "accel/bvh_build.h"
#include "accel/bvh_collapse.h"
#include "accel/bvh_collapse_plan.h"
#include "accel/bvh_node_box.h"
#include "accel/bvh_walk.h"
#include "accel/tuned_bvh.h"
#include "same_answers.h"
#include "test_geometry.h"

namespace tuneray::test {
namespace {

struct Built {
  bvh::Tree tree;
  bvh::PrimitiveCache cache;
  bvh::BuildResult result;
};

// The tree as Embree's builder shapes it (collapse_to_wide is called by the tests).
void build(const Mesh& mesh, const std::string& text, Built& out) {
  out.result = bvh::build_tree(mesh.view(), parse_bvh_config(text), *EmbreeDevice::shared(),
                               out.cache, out.tree);
}

bool box_contains(const BBox& outer, const BBox& inner) {
  for (int a = 0; a < 3; ++a)
    if (inner.lo[a] < outer.lo[a] || inner.hi[a] > outer.hi[a]) return false;
  return true;
}

// Walks an 8-wide tree and checks, node by node: no node could take in one more inner child
// (every inner child has more children than the free slots plus the one it would free), and
// every child box contains the boxes of its own children, down to the triangles of the leaves.
struct WideCounts {
  size_t nodes = 0, leaves = 0, not_maximal = 0, not_containing = 0;
};

template <bool kCompact>
struct WideCheck : WideCounts {
  using Node = bvh::NodeOf<8, kCompact>;
  const Mesh& mesh;
  explicit WideCheck(const Mesh& m) : mesh(m) {}

  BBox leaf_box(bvh::NodeRef ref) {
    const bvh::LeafHeader* leaf = bvh::leaf_header(ref);
    BBox box;
    if constexpr (kCompact) {
      const uint32_t* ids = bvh::leaf_ids(ref);
      for (uint32_t i = 0; i < leaf->prim_count; ++i)
        for (uint32_t v : mesh.triangles[ids[i]].v) box.extend(mesh.positions[v]);
    } else {
      const auto* packs = bvh::leaf_packs(ref);
      for (uint32_t i = 0; i < leaf->prim_count; ++i)
        for (uint32_t v : mesh.triangles[packs[i / 4].prim[i % 4]].v) box.extend(mesh.positions[v]);
    }
    return box;
  }

  // Returns the box of everything below `ref`.
  BBox visit(bvh::NodeRef ref) {
    if (bvh::is_leaf(ref)) {
      ++leaves;
      return leaf_box(ref);
    }
    ++nodes;
    const Node& n = *bvh::ref_ptr<Node>(ref);
    const int count = bvh::child_count<8, kCompact>(n);
    BBox all;
    for (int i = 0; i < 8; ++i) {
      if (n.child[i] == bvh::kEmptyRef) continue;
      if (!bvh::is_leaf(n.child[i])) {
        const int grandchildren = bvh::child_count<8, kCompact>(*bvh::ref_ptr<Node>(n.child[i]));
        // The source node it grew from had at most `grandchildren` children: had those fitted,
        // the greedy rule would have opened it.
        if (count - 1 + grandchildren <= 8) ++not_maximal;
      }
      BBox below = visit(n.child[i]);
      if (!box_contains(bvh::child_box<8, kCompact>(n, i), below)) ++not_containing;
      all.extend(below);
    }
    return all;
  }
};

WideCounts check_wide_tree(const Mesh& mesh, const bvh::Tree& tree) {
  auto run = [&](auto check) -> WideCounts {
    check.visit(tree.root());
    return check;
  };
  return tree.shape().compact ? run(WideCheck<true>(mesh)) : run(WideCheck<false>(mesh));
}

class Collapse : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { mesh_ = new Mesh(make_soup(20000, 33)); }
  static void TearDownTestSuite() { delete mesh_; }
  static Mesh* mesh_;
};
Mesh* Collapse::mesh_ = nullptr;

TEST_F(Collapse, KeepsEveryLeafAndFillsTheNodes) {
  // Without spatial splits, so that every leaf's triangles lie inside the boxes above it.
  for (bool optimal : {false, true})
    for (const char* text : {"branching=2", "branching=4", "branching=2,compact=1",
                             "branching=4,compact=1,max_leaf=4"}) {
      SCOPED_TRACE(std::string(text) + (optimal ? ", optimal" : ", greedy"));
      Built source, collapsed;
      build(*mesh_, text, source);
      build(*mesh_, text, collapsed);
      const bvh::TreeStats before = bvh::measure_tree(source.tree, 1.0, 1.0);
      EXPECT_EQ(collapsed.result.inner_nodes, before.node_count);
      bvh::collapse_to_wide(collapsed.tree, collapsed.result.inner_nodes, 0, 1.0f, optimal);
      ASSERT_EQ(collapsed.tree.shape().width, 8);
      ASSERT_TRUE(collapsed.tree.collapsed());
      ASSERT_FALSE(collapsed.tree.relaid_out());
      const bvh::TreeStats after = bvh::measure_tree(collapsed.tree, 1.0, 1.0);
      EXPECT_EQ(after.leaf_count, before.leaf_count);
      EXPECT_EQ(after.references, before.references);
      EXPECT_EQ(after.leaf_code_mismatches, 0u);
      // A wide node takes the place of several binary ones; of 4-wide nodes, two at most.
      if (source.tree.shape().width == 2)
        EXPECT_LT(after.node_count * 3, before.node_count);
      else
        EXPECT_LT(after.node_count, before.node_count);
      EXPECT_LT(after.depth, before.depth);

      const WideCounts wide = check_wide_tree(*mesh_, collapsed.tree);
      EXPECT_EQ(wide.nodes, after.node_count);
      EXPECT_EQ(wide.leaves, before.leaf_count);
      // (The plan leaves a slot free where opening a child would cost more than its visit.)
      if (!optimal) {
        EXPECT_EQ(wide.not_maximal, 0u);
      }
      EXPECT_EQ(wide.not_containing, 0u);
    }
}

// With leaves priced in packs of 4 (what TunedBvhAccel asks for), small subtrees become leaves
// and sibling leaves merge: far fewer leaves and nodes, none above the limit, every reference
// kept, boxes still containing their triangles.
TEST_F(Collapse, MergedLeavesKeepEveryReferenceAndStayWithinTheLimit) {
  for (bool optimal : {false, true})
    for (const char* text : {"branching=2", "branching=4", "branching=2,max_leaf=6",
                             "branching=2,robust=1", "branching=2,compact=1"}) {
      SCOPED_TRACE(std::string(text) + (optimal ? ", optimal" : ", greedy"));
      const bool compact = std::string(text).find("compact") != std::string::npos;
      const int limit = parse_bvh_config(text).max_leaf;
      Built source, merged;
      build(*mesh_, text, source);
      build(*mesh_, text, merged);
      const bvh::TreeStats before = bvh::measure_tree(source.tree, 1.0, 1.0);
      bvh::collapse_to_wide(merged.tree, merged.result.inner_nodes, limit, 1.0f, optimal);
      const bvh::TreeStats after = bvh::measure_tree(merged.tree, 1.0, 1.0);
      EXPECT_EQ(after.references, before.references);
      EXPECT_LE(after.max_leaf_size, static_cast<size_t>(limit));
      EXPECT_EQ(after.leaf_code_mismatches, 0u);
      if (compact) {
        EXPECT_EQ(after.leaf_count, before.leaf_count);  // compact leaves are never merged
      } else {
        EXPECT_LT(after.leaf_count * 3, before.leaf_count * 2);
        EXPECT_LT(after.node_count * 4, before.node_count);
      }
      // (Not the greedy rule's fullness: a wide child may hold fewer children than the source node
      // the rule saw, once its own leaves merged.)
      const WideCounts wide = check_wide_tree(*mesh_, merged.tree);
      EXPECT_EQ(wide.leaves, after.leaf_count);
      EXPECT_EQ(wide.not_containing, 0u);
    }
}

// The pack's price steers the leaves: the dearer a pack test against a node visit, the fewer
// triangles a merged leaf holds on average, and every price keeps every reference.
TEST_F(Collapse, DearerPacksMakeSmallerLeaves) {
  double previous = 1e9;
  for (float pack_cost : {0.5f, 1.0f, 4.0f, 16.0f}) {
    SCOPED_TRACE(pack_cost);
    Built source, merged;
    build(*mesh_, "branching=2", source);
    build(*mesh_, "branching=2", merged);
    bvh::collapse_to_wide(merged.tree, merged.result.inner_nodes, 32, pack_cost);
    const bvh::TreeStats before = bvh::measure_tree(source.tree, 1.0, 1.0);
    const bvh::TreeStats after = bvh::measure_tree(merged.tree, 1.0, 1.0);
    EXPECT_EQ(after.references, before.references);
    const double per_leaf =
        static_cast<double>(after.references) / static_cast<double>(after.leaf_count);
    EXPECT_LE(per_leaf, previous);
    previous = per_leaf;
  }
  EXPECT_LT(previous, 3.0);  // at 16 the build's own small leaves stay almost as they were
}

// Without merged leaves the plan's optimum is the written tree's cost, to rounding: an
// independent walk of the 8-wide tree (node visits and pack tests weighted by area) agrees with
// the dynamic programme's value, and the greedy rule's tree is never cheaper.
template <int N>
double planned_cost(const bvh::Tree& tree) {
  const auto& root = *bvh::ref_ptr<bvh::NodeOf<N, false>>(tree.root());
  BBox box;
  for (int i = 0; i < N; ++i)
    if (root.child[i] != bvh::kEmptyRef) box.extend(bvh::child_box<N, false>(root, i));
  const bvh::CollapsePlan<N, false> plan(tree.root(), 0, 0, 1.0f);
  return 1.0 + plan.cost(plan.root(), 8) / box.surface_area();
}

TEST_F(Collapse, TheOptimalPlanCostsWhatItSaysAndNeverMoreThanTheGreedyRule) {
  bool cheaper_somewhere = false;
  for (const char* text : {"branching=2", "branching=4", "branching=2,sah_block_size=4",
                           "branching=2,max_leaf=4,quality=high"}) {
    SCOPED_TRACE(text);
    Built greedy, optimal;
    build(*mesh_, text, greedy);
    build(*mesh_, text, optimal);
    const double planned = optimal.tree.shape().width == 2 ? planned_cost<2>(optimal.tree)
                                                           : planned_cost<4>(optimal.tree);
    bvh::collapse_to_wide(greedy.tree, greedy.result.inner_nodes, 0, 1.0f, false);
    bvh::collapse_to_wide(optimal.tree, optimal.result.inner_nodes, 0, 1.0f, true);
    const bvh::TreeStats g = bvh::measure_tree(greedy.tree, 1.0, 1.0);
    const bvh::TreeStats o = bvh::measure_tree(optimal.tree, 1.0, 1.0);
    EXPECT_NEAR(o.pack_sah_cost, planned, 1e-5 * planned);
    EXPECT_LE(o.pack_sah_cost, g.pack_sah_cost * (1.0 + 1e-6));
    if (o.pack_sah_cost < 0.99 * g.pack_sah_cost) cheaper_somewhere = true;
    EXPECT_EQ(o.references, g.references);
    EXPECT_EQ(o.leaf_count, g.leaf_count);
  }
  EXPECT_TRUE(cheaper_somewhere);
}

TEST_F(Collapse, RaysFindExactlyWhatTheUncollapsedTreeFinds) {
  std::vector<Ray> rays;
  Pcg32 rng(7);
  for (int i = 0; i < 4000; ++i)
    rays.push_back(
        Ray{random_point(rng, mesh_->bounds()), 0, random_direction(rng), 0.2f * rng.next_float()});
  for (const char* text :
       {"branching=2", "branching=4,max_leaf=4", "branching=2,compact=1", "branching=2,robust=1",
        "branching=2,quality=high", "branching=2,static=1", "branching=4,compact=1,static=1",
        "branching=2,optimal_collapse=1", "branching=4,max_leaf=4,optimal_collapse=1",
        "branching=2,compact=1,robust=1,optimal_collapse=1",
        "branching=2,quality=high,static=1,optimal_collapse=1"}) {
    SCOPED_TRACE(text);
    TunedBvhAccel plain(parse_bvh_config(std::string(text) + ",collapse=0"));
    TunedBvhAccel wide(parse_bvh_config(std::string(text) + ",collapse=1"));
    plain.build(mesh_->view());
    BuildStats stats = wide.build(mesh_->view());
    EXPECT_LT(stats.node_count, plain.tree_stats().node_count);
    const auto [hits, blocked] = expect_same_answers(plain, wide, rays);
    // Both answers occur (the rays end inside the soup).
    EXPECT_GT(hits, 0u);
    EXPECT_LT(hits, rays.size());
    EXPECT_EQ(blocked, hits);
  }
}

TEST_F(Collapse, HasNoEffectAtBranchingEight) {
  TunedBvhAccel plain(parse_bvh_config("branching=8,collapse=0"));
  TunedBvhAccel wide(parse_bvh_config("branching=8,collapse=1"));
  BuildStats a = plain.build(mesh_->view()), b = wide.build(mesh_->view());
  EXPECT_EQ(a.node_count, b.node_count);
  EXPECT_EQ(a.leaf_count, b.leaf_count);
  EXPECT_EQ(a.sah_cost, b.sah_cost);
}

TEST_F(Collapse, ATreeThatIsOneLeafStaysOneLeaf) {
  Mesh small;
  small.add(Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0));
  TunedBvhAccel wide(parse_bvh_config("branching=2,collapse=1"));
  BuildStats stats = wide.build(small.view());
  EXPECT_EQ(stats.node_count, 0u);
  EXPECT_EQ(stats.leaf_count, 1u);
  Hit hit;
  const Vec3f a = small.positions[0], b = small.positions[1], c = small.positions[2];
  const Vec3f centre = (a + b + c) / 3.0f;
  const Vec3f n = normalize(cross(b - a, c - a));
  ASSERT_TRUE(wide.intersect(Ray{centre + n, 0, -n, kInf}, hit));
  EXPECT_EQ(hit.prim, 0u);
}

}  // namespace
}  // namespace tuneray::test
