#include "accel/bvh_collapse.h"

#include <cstdlib>
#include <memory>
#include <new>
#include <stdexcept>

#include "accel/bvh_node_box.h"

namespace tuneray::bvh {

namespace {

constexpr int kWide = BvhConfig::kCollapsedWidth;

template <int N, bool kCompact>
class Collapser {
 public:
  using Source = NodeOf<N, kCompact>;
  using Wide = NodeOf<kWide, kCompact>;

  static void run(Tree& tree, size_t max_inner_nodes) {
    // Every wide node takes the place of at least one source node, so the source's count bounds
    // the buffer; pages past the nodes written are never touched.
    const size_t bytes = max_inner_nodes * whole_lines(sizeof(Wide));
    std::unique_ptr<char, decltype(&std::free)> buffer(
        static_cast<char*>(std::aligned_alloc(kCacheLine, bytes)), &std::free);
    if (!buffer) throw std::bad_alloc();
    Collapser c;
    c.base_ = buffer.get();
    c.capacity_ = max_inner_nodes;
    const NodeRef root = c.collapse(tree.root());
    TreeShape shape = tree.shape();
    shape.width = kWide;
    tree.adopt_collapsed(buffer.release(), c.used_ * whole_lines(sizeof(Wide)), root, shape);
  }

 private:
  struct Slot {
    BBox box;
    NodeRef ref;
    float area;
    int children;  // of a source inner node; 0 for a leaf
  };

  static Slot slot(const Source& parent, int i) {
    Slot s{child_box<N, kCompact>(parent, i), parent.child[i], 0.0f, 0};
    s.area = s.box.surface_area();
    if (!is_leaf(s.ref)) s.children = child_count<N, kCompact>(*ref_ptr<Source>(s.ref));
    return s;
  }

  // Writes the wide node that replaces source inner node `ref`, then, depth first, those below
  // it; returns its reference. Leaves stay where the build put them.
  NodeRef collapse(NodeRef ref) {
    Slot slots[kWide];
    int count = 0;
    const Source& top = *ref_ptr<Source>(ref);
    for (int i = 0; i < N; ++i)
      if (top.child[i] != kEmptyRef) slots[count++] = slot(top, i);
    for (;;) {
      int best = -1;
      for (int i = 0; i < count; ++i) {
        if (slots[i].children == 0 || count - 1 + slots[i].children > kWide) continue;
        if (best < 0 || slots[i].area > slots[best].area) best = i;
      }
      if (best < 0) break;
      // The opened node's first child takes its slot, the others go to the end.
      const Source& opened = *ref_ptr<Source>(slots[best].ref);
      int target = best;
      for (int i = 0; i < N; ++i) {
        if (opened.child[i] == kEmptyRef) continue;
        slots[target] = slot(opened, i);
        target = count++;
      }
      --count;  // the opened node's own slot was reused
    }

    if (used_ == capacity_) throw std::logic_error("BVH collapse: more nodes than the build made");
    auto* node = reinterpret_cast<Wide*>(base_ + used_++ * whole_lines(sizeof(Wide)));
    clear_node<kWide, kCompact>(*node);
    BBox boxes[kWide];
    for (int i = 0; i < count; ++i) boxes[i] = slots[i].box;
    set_child_boxes<kWide, kCompact>(*node, boxes, count);
    for (int i = 0; i < count; ++i)
      node->child[i] = is_leaf(slots[i].ref) ? slots[i].ref : collapse(slots[i].ref);
    return make_node_ref(node);
  }

  char* base_ = nullptr;
  size_t used_ = 0, capacity_ = 0;
};

template <bool kCompact>
void collapse(Tree& tree, size_t max_inner_nodes) {
  if (tree.shape().width == 2)
    Collapser<2, kCompact>::run(tree, max_inner_nodes);
  else
    Collapser<4, kCompact>::run(tree, max_inner_nodes);
}

}  // namespace

void collapse_to_wide(Tree& tree, size_t max_inner_nodes) {
  const NodeRef root = tree.root();
  if (tree.shape().width >= kWide || root == kEmptyRef || is_leaf(root) || tree.relaid_out() ||
      tree.collapsed())
    return;
  if (tree.shape().compact)
    collapse<true>(tree, max_inner_nodes);
  else
    collapse<false>(tree, max_inner_nodes);
}

}  // namespace tuneray::bvh
