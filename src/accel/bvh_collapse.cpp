#include "accel/bvh_collapse.h"

#include <cstdlib>
#include <cstring>
#include <new>
#include <vector>

#include "accel/bvh_node_box.h"
#include "accel/bvh_walk.h"

namespace tuneray::bvh {

namespace {

constexpr int kWide = kCollapsedWidth;

template <int N, bool kCompact>
class Collapser {
 public:
  using Source = NodeOf<N, kCompact>;
  using Wide = NodeOf<kWide, kCompact>;

  static void run(Tree& tree) {
    Collapser c;
    const NodeRef root = tree.root();
    c.plan(root);
    size_t bytes = c.nodes_.size() * whole_lines(sizeof(Wide)) + c.leaf_bytes_;
    char* buffer = static_cast<char*>(std::aligned_alloc(kCacheLine, whole_lines(bytes)));
    if (!buffer) throw std::bad_alloc();
    size_t offset = 0;
    NodeRef new_root = c.write(0, buffer, offset);
    TreeShape shape = tree.shape();
    shape.width = kWide;
    tree.adopt_buffer(buffer, bytes, new_root, shape);
  }

 private:
  // A child slot of a wide node: a source leaf, or (wide >= 0) the wide node planned for it.
  struct Slot {
    BBox box;
    NodeRef source;
    int wide = -1;
  };
  struct Plan {
    Slot slots[kWide];
    int count = 0;
  };

  // Plans the wide node for the source inner node `ref` and, depth first, those below it.
  int plan(NodeRef ref) {
    Plan p;
    open(ref, p, -1);
    for (;;) {
      int best = -1;
      float best_area = -1.0f;
      for (int i = 0; i < p.count; ++i) {
        const NodeRef r = p.slots[i].source;
        if (is_leaf(r)) continue;
        if (p.count - 1 + child_count<N, kCompact>(*ref_ptr<Source>(r)) > kWide) continue;
        const float area = p.slots[i].box.surface_area();
        if (area > best_area) {
          best_area = area;
          best = i;
        }
      }
      if (best < 0) break;
      open(p.slots[best].source, p, best);
    }
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back(p);
    for (int i = 0; i < p.count; ++i) {
      const NodeRef r = p.slots[i].source;
      if (is_leaf(r)) {
        leaf_bytes_ += whole_lines(leaf_bytes(ref_ptr<LeafHeader>(r), kCompact));
      } else {
        const int child = plan(r);
        nodes_[static_cast<size_t>(index)].slots[i].wide = child;
      }
    }
    return index;
  }

  // Puts the children of source node `ref` into `p`: into slot `replace` (the slot that held
  // `ref`) and after the last slot.
  static void open(NodeRef ref, Plan& p, int replace) {
    const Source& n = *ref_ptr<Source>(ref);
    for (int i = 0; i < N; ++i) {
      if (n.child[i] == kEmptyRef) continue;
      Slot s{child_box<N, kCompact>(n, i), n.child[i], -1};
      if (replace >= 0) {
        p.slots[replace] = s;
        replace = -1;
      } else {
        p.slots[p.count++] = s;
      }
    }
  }

  // The node, then its leaves (a ray that enters them has just read the node), then each inner
  // child's subtree in turn.
  NodeRef write(int index, char* base, size_t& offset) const {
    auto* node = reinterpret_cast<Wide*>(base + offset);
    offset += whole_lines(sizeof(Wide));
    const Plan& p = nodes_[static_cast<size_t>(index)];
    clear_node<kWide, kCompact>(*node);
    BBox boxes[kWide];
    for (int i = 0; i < p.count; ++i) boxes[i] = p.slots[i].box;
    set_child_boxes<kWide, kCompact>(*node, boxes, p.count);
    for (int i = 0; i < p.count; ++i) {
      const NodeRef r = p.slots[i].source;
      if (!is_leaf(r)) continue;
      const auto* leaf = ref_ptr<LeafHeader>(r);
      char* dst = base + offset;
      offset += whole_lines(leaf_bytes(leaf, kCompact));
      std::memcpy(dst, leaf, leaf_bytes(leaf, kCompact));
      node->child[i] = make_leaf_ref(dst, leaf_code(r));
    }
    for (int i = 0; i < p.count; ++i)
      if (p.slots[i].wide >= 0) node->child[i] = write(p.slots[i].wide, base, offset);
    return make_node_ref(node);
  }

  std::vector<Plan> nodes_;
  size_t leaf_bytes_ = 0;
};

template <bool kCompact>
void collapse(Tree& tree) {
  if (tree.shape().width == 2)
    Collapser<2, kCompact>::run(tree);
  else
    Collapser<4, kCompact>::run(tree);
}

}  // namespace

void collapse_to_wide(Tree& tree) {
  const NodeRef root = tree.root();
  if (tree.shape().width >= kWide || root == kEmptyRef || is_leaf(root) || tree.relaid_out()) {
    relayout_depth_first(tree);
    return;
  }
  if (tree.shape().compact)
    collapse<true>(tree);
  else
    collapse<false>(tree);
}

}  // namespace tuneray::bvh
