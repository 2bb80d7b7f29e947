#include "accel/bvh_collapse.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>

#include "accel/bvh_collapse_plan.h"
#include "accel/bvh_node_box.h"
#include "accel/ray_sample.h"
#include "math/ray.h"

namespace tuneray::bvh {

namespace {

constexpr int kWide = BvhConfig::kCollapsedWidth;
// Source leaves in one merged leaf: a merged slot keeps growing over the rounds of opening and
// merging, but each source leaf brings a triangle at least, and leaves hold at most 32.
constexpr int kMaxParts = 32;

template <int N, bool kCompact>
class Collapser {
 public:
  using Source = NodeOf<N, kCompact>;
  using Wide = NodeOf<kWide, kCompact>;

  static void run(Tree& tree, size_t max_inner_nodes, int merge_limit, float pack_cost,
                  bool optimal, const BoxMeasure& measure) {
    // Every wide node takes the place of at least one source node, so the source's count bounds
    // the buffer; pages past the nodes written are never touched.
    const size_t bytes = max_inner_nodes * whole_lines(sizeof(Wide));
    using Buffer = std::unique_ptr<char, decltype(&std::free)>;
    Buffer buffer(static_cast<char*>(tree_alloc(bytes)), &std::free);
    Collapser c;
    c.measure_ = measure;
    c.base_ = buffer.get();
    c.capacity_ = max_inner_nodes;
    // A merged leaf takes no more lines than the leaves it is made of, so theirs bound the
    // merged leaves' buffer.
    Buffer leaves(nullptr, &std::free);
    if (!kCompact && merge_limit > 1) {
      const size_t leaf_capacity = whole_lines(leaf_lines_below(tree.root()));
      leaves.reset(static_cast<char*>(tree_alloc(leaf_capacity)));
      c.merge_limit_ = merge_limit;
      c.flatten_limit_ = merge_limit;
      c.pack_cost_ = pack_cost;
      c.leaf_base_ = leaves.get();
      c.leaf_capacity_ = leaf_capacity;
    }
    if (optimal)
      c.plan_ = std::make_unique<CollapsePlan<N, kCompact>>(
          tree.root(), max_inner_nodes, c.flatten_limit_, merge_limit > 1 ? pack_cost : 1.0f,
          measure);
    const NodeRef root = c.plan_ ? c.collapse_planned(c.plan_->root()) : c.collapse(tree.root());
    TreeShape shape = tree.shape();
    shape.width = kWide;
    if (c.leaf_used_ == 0) leaves.reset();
    tree.adopt_collapsed(buffer.release(), c.used_ * whole_lines(sizeof(Wide)), root, shape,
                         leaves.release());
  }

 private:
  struct Slot {
    BBox box;
    NodeRef ref;
    float area;
    int children;   // of a source inner node; 0 for a leaf
    int triangles;  // of a leaf
    int parts;      // source leaves a leaf is made of (1 unless merged)
    int plan;       // the source node's index in plan_, or -1 without a plan
    NodeRef part[kMaxParts];
  };

  Slot slot(const Source& parent, int i, int plan = -1) const {
    Slot s{child_box<N, kCompact>(parent, i), parent.child[i], 0.0f, 0, 0, 1, plan, {}};
    s.area = measure_(s.box);
    s.part[0] = s.ref;
    if (is_leaf(s.ref)) {
      s.triangles = static_cast<int>(leaf_header(s.ref)->prim_count);
    } else if (plan >= 0 ? plan_->as_leaf(plan) : flatten_limit_ > 0 && flattens(s.ref, s.area)) {
      s.parts = 0;
      collect_leaves(s.ref, s);
    } else {
      s.children = child_count<N, kCompact>(*ref_ptr<Source>(s.ref));
    }
    return s;
  }

  float packs_cost(int triangles) const { return packs_price(pack_cost_, triangles); }

  // Triangles below `ref`, or flatten_limit_ + 1 as soon as there are more.
  int triangles_below(NodeRef ref) const {
    if (is_leaf(ref)) return static_cast<int>(leaf_header(ref)->prim_count);
    const Source& n = *ref_ptr<Source>(ref);
    int sum = 0;
    for (int i = 0; i < N && sum <= flatten_limit_; ++i)
      if (n.child[i] != kEmptyRef) sum += triangles_below(n.child[i]);
    return std::min(sum, flatten_limit_ + 1);
  }

  // The SAH cost of the subtree at `ref` (box area `area`) as built or, where cheaper, with a
  // small subtree made one leaf: a node visit costs 1, a leaf one per pack of 4 (Embree's SAH
  // with blocks of 4, as its BVH8 builds for its triangle packs; the build was asked for blocks
  // of one triangle, which in packs of 4 wastes lanes and nodes).
  float best_cost(NodeRef ref, float area, int& triangles) const {
    if (is_leaf(ref)) {
      triangles = static_cast<int>(leaf_header(ref)->prim_count);
      return area * packs_cost(triangles);
    }
    const Source& n = *ref_ptr<Source>(ref);
    float cost = area;
    triangles = 0;
    for (int i = 0; i < N; ++i) {
      if (n.child[i] == kEmptyRef) continue;
      int t = 0;
      cost += best_cost(n.child[i], measure_(child_box<N, kCompact>(n, i)), t);
      triangles += t;
    }
    if (triangles <= flatten_limit_) cost = std::min(cost, area * packs_cost(triangles));
    return cost;
  }

  // Whether the inner node `ref` becomes one leaf: it holds few enough triangles, and one leaf
  // of them costs no more than the best subtree.
  bool flattens(NodeRef ref, float area) const {
    if (triangles_below(ref) > flatten_limit_) return false;
    int triangles = 0;
    const Source& n = *ref_ptr<Source>(ref);
    float tree = area;
    for (int i = 0; i < N; ++i) {
      if (n.child[i] == kEmptyRef) continue;
      int t = 0;
      tree += best_cost(n.child[i], measure_(child_box<N, kCompact>(n, i)), t);
      triangles += t;
    }
    return area * packs_cost(triangles) <= tree;
  }

  void collect_leaves(NodeRef ref, Slot& s) const {
    if (is_leaf(ref)) {
      s.part[s.parts++] = ref;
      s.triangles += static_cast<int>(leaf_header(ref)->prim_count);
      return;
    }
    const Source& n = *ref_ptr<Source>(ref);
    for (int i = 0; i < N; ++i)
      if (n.child[i] != kEmptyRef) collect_leaves(n.child[i], s);
  }

  static size_t leaf_lines_below(NodeRef ref) {
    if (is_leaf(ref)) return whole_lines(leaf_bytes(*leaf_header(ref), kCompact));
    const Source& n = *ref_ptr<Source>(ref);
    size_t bytes = 0;
    for (int i = 0; i < N; ++i)
      if (n.child[i] != kEmptyRef) bytes += leaf_lines_below(n.child[i]);
    return bytes;
  }

  // Expected cost of a leaf by the surface area heuristic: the rays that enter its box pay a
  // visit and one test per pack of 4, so a pack of 1 triangle costs what a pack of 4 does (the
  // build's SAH counted triangles one by one and made leaves of 1-2 triangles).
  float leaf_cost(float area, int triangles) const { return area * (1.0f + packs_cost(triangles)); }

  // Merges the wide node's leaf children pairwise while a merge lowers their summed leaf cost,
  // the best merge first, up to merge_limit_ triangles a leaf. Returns whether any was merged.
  bool merge_leaves(Slot* slots, int& count) const {
    bool merged = false;
    for (;;) {
      int best_i = -1, best_j = -1;
      float best_saving = 0.0f;
      BBox best_box;
      for (int i = 0; i < count; ++i) {
        if (slots[i].children != 0) continue;
        for (int j = i + 1; j < count; ++j) {
          if (slots[j].children != 0) continue;
          const int triangles = slots[i].triangles + slots[j].triangles;
          if (triangles > merge_limit_ || slots[i].parts + slots[j].parts > kMaxParts) continue;
          BBox box = slots[i].box;
          box.extend(slots[j].box);
          const float saving = leaf_cost(slots[i].area, slots[i].triangles) +
                               leaf_cost(slots[j].area, slots[j].triangles) -
                               leaf_cost(measure_(box), triangles);
          if (saving > best_saving) {
            best_saving = saving;
            best_i = i;
            best_j = j;
            best_box = box;
          }
        }
      }
      if (best_i < 0) return merged;
      Slot& into = slots[best_i];
      const Slot& from = slots[best_j];
      into.box = best_box;
      into.area = measure_(best_box);
      into.triangles += from.triangles;
      for (int k = 0; k < from.parts; ++k) into.part[into.parts++] = from.part[k];
      slots[best_j] = slots[--count];
      merged = true;
    }
  }

  // Writes a leaf holding the triangles of a merged slot's source leaves, in their order, packed
  // 4 to a pack (unused lanes as the build leaves them: zero geometry, invalid index).
  NodeRef write_merged_leaf(const Slot& s) {
    const uint32_t packs = static_cast<uint32_t>((s.triangles + 3) / 4);
    const LeafHeader header{static_cast<uint32_t>(s.triangles), packs};
    const size_t bytes = whole_lines(leaf_bytes(header, false));
    if (leaf_used_ + bytes > leaf_capacity_)
      throw std::logic_error("BVH collapse: merged leaves larger than their sources");
    char* leaf = leaf_base_ + leaf_used_;
    leaf_used_ += bytes;
    write_leaf_header(leaf, header);
    auto* out = reinterpret_cast<TriPack4*>(leaf);
    std::memset(static_cast<void*>(out), 0, packs * sizeof(TriPack4));
    for (uint32_t k = 0; k < packs; ++k)
      for (int lane = 0; lane < 4; ++lane) out[k].prim[lane] = kInvalidId;
    uint32_t next = 0;
    for (int p = 0; p < s.parts; ++p) {
      const TriPack4* in = leaf_packs(s.part[p]);
      const uint32_t source_triangles = leaf_header(s.part[p])->prim_count;
      for (uint32_t t = 0; t < source_triangles; ++t, ++next) {
        const TriPack4& a = in[t / 4];
        TriPack4& b = out[next / 4];
        for (int row = 0; row < 9; ++row) b.p[row][next % 4] = a.p[row][t % 4];
        b.prim[next % 4] = a.prim[t % 4];
      }
    }
    return make_leaf_ref(leaf, packs);
  }

  // Writes the wide node that replaces source inner node `ref`, then, depth first, those below
  // it; returns its reference. Leaves stay where the build put them.
  NodeRef collapse(NodeRef ref) {
    Slot slots[kWide];
    int count = 0;
    const Source& top = *ref_ptr<Source>(ref);
    for (int i = 0; i < N; ++i)
      if (top.child[i] != kEmptyRef) slots[count++] = slot(top, i);
    // Merging leaves frees slots for the greedy rule to open more inner children, whose leaves
    // may merge in turn.
    do {
      open_children(slots, count);
    } while (merge_limit_ > 1 && merge_leaves(slots, count));

    return write_node(slots, count);
  }

  // Writes a wide node of these children, then, depth first, the wide nodes below it.
  NodeRef write_node(const Slot* slots, int count) {
    if (used_ == capacity_) throw std::logic_error("BVH collapse: more nodes than the build made");
    auto* node = reinterpret_cast<Wide*>(base_ + used_++ * whole_lines(sizeof(Wide)));
    clear_node<kWide, kCompact>(*node);
    BBox boxes[kWide];
    for (int i = 0; i < count; ++i) boxes[i] = slots[i].box;
    set_child_boxes<kWide, kCompact>(*node, boxes, count);
    for (int i = 0; i < count; ++i) {
      const Slot& c = slots[i];
      if (c.children > 0)
        node->child[i] = c.plan >= 0 ? collapse_planned(c.plan) : collapse(c.ref);
      else  // a leaf as built, or one made of several (merged, or an inner node flattened)
        node->child[i] = c.parts == 1 && is_leaf(c.ref) ? c.ref : write_merged_leaf(c);
    }
    return make_node_ref(node);
  }

  // The greedy rule: the inner child with the largest surface area whose children still fit is
  // replaced by them, until none fits.
  void open_children(Slot* slots, int& count) const {
    for (;;) {
      int best = -1;
      for (int i = 0; i < count; ++i) {
        if (slots[i].children == 0 || count - 1 + slots[i].children > kWide) continue;
        if (best < 0 || slots[i].area > slots[best].area) best = i;
      }
      if (best < 0) break;
      // The opened node's first child takes its slot, the others go to the end.
      const Source& opened = *ref_ptr<Source>(slots[best].ref);
      const int opened_plan = slots[best].plan;
      int target = best;
      for (int i = 0; i < N; ++i) {
        if (opened.child[i] == kEmptyRef) continue;
        slots[target] = slot(opened, i, opened_plan >= 0 ? plan_->child(opened_plan, i) : -1);
        target = count++;
      }
      --count;  // the opened node's own slot was reused
    }
  }

  // Writes the wide node the plan makes of the source inner node at plan index `index`.
  NodeRef collapse_planned(int index) {
    Slot slots[kWide];
    int count = 0;
    plan_->spread(index, [&](const Source& parent, int i, int child) {
      slots[count++] = slot(parent, i, child);
    });
    // Leaves merge as below, but the slots they free stay free: the greedy rule would open a
    // child the plan kept whole, each of its children then taking one slot where the plan gave
    // some more, which costs more than the visit it saves.
    if (merge_limit_ > 1) merge_leaves(slots, count);
    return write_node(slots, count);
  }

  std::unique_ptr<const CollapsePlan<N, kCompact>> plan_;
  BoxMeasure measure_;  // what a box costs the rays that visit it (its area unless weighted)
  char* base_ = nullptr;
  size_t used_ = 0, capacity_ = 0;
  int merge_limit_ = 0;
  int flatten_limit_ = 0;   // inner nodes with at most this many triangles may become leaves
  float pack_cost_ = 1.0f;  // a pack test's cost over a node visit's
  char* leaf_base_ = nullptr;
  size_t leaf_used_ = 0, leaf_capacity_ = 0;
};

template <bool kCompact>
void collapse(Tree& tree, size_t max_inner_nodes, int merge_limit, float pack_cost, bool optimal,
              const BoxMeasure& measure) {
  if (tree.shape().width == 2)
    Collapser<2, kCompact>::run(tree, max_inner_nodes, merge_limit, pack_cost, optimal, measure);
  else
    Collapser<4, kCompact>::run(tree, max_inner_nodes, merge_limit, pack_cost, optimal, measure);
}

}  // namespace

void collapse_to_wide(Tree& tree, size_t max_inner_nodes, int merge_leaves_up_to, float pack_cost,
                      bool optimal, const BoxMeasure& measure) {
  const NodeRef root = tree.root();
  if (tree.shape().width >= kWide || root == kEmptyRef || is_leaf(root) || tree.relaid_out() ||
      tree.collapsed())
    return;
  if (tree.shape().compact)
    collapse<true>(tree, max_inner_nodes, merge_leaves_up_to, pack_cost, optimal, measure);
  else
    collapse<false>(tree, max_inner_nodes, merge_leaves_up_to, pack_cost, optimal, measure);
}

}  // namespace tuneray::bvh
