#include "accel/bvh_walk.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <type_traits>

#include "accel/bvh_node_box.h"
#include "math/bbox.h"

namespace tuneray::bvh {

namespace {

template <int N, bool kCompact>
struct Walker {
  using Node = NodeOf<N, kCompact>;

  static BBox child_box(const Node& n, int i) { return bvh::child_box<N, kCompact>(n, i); }

  static BBox node_box(const Node& n) {
    BBox box;
    for (int i = 0; i < N; ++i) {
      if (n.child[i] != kEmptyRef) box.extend(child_box(n, i));
    }
    return box;
  }

  static void stats(NodeRef ref, double area, int level, double trav, double isect, TreeStats& s) {
    s.depth = std::max(s.depth, level);
    if (is_leaf(ref)) {
      const LeafHeader* leaf = leaf_header(ref);
      s.leaf_count++;
      s.references += leaf->prim_count;
      s.max_leaf_size = std::max<size_t>(s.max_leaf_size, leaf->prim_count);
      s.leaf_bytes += leaf_bytes(*leaf, kCompact);
      s.sah_cost += isect * area * leaf->prim_count;
      s.pack_sah_cost += isect * area * ((leaf->prim_count + 3) / 4);
      if (!kCompact && leaf_code(ref) != leaf->pack_count) s.leaf_code_mismatches++;
      return;
    }
    const Node& n = *ref_ptr<Node>(ref);
    s.node_count++;
    s.node_bytes += sizeof(Node);
    s.sah_cost += trav * area;
    s.pack_sah_cost += trav * area;
    for (int i = 0; i < N; ++i) {
      if (n.child[i] == kEmptyRef) continue;
      stats(n.child[i], child_box(n, i).surface_area(), level + 1, trav, isect, s);
    }
  }

  static TreeStats measure(NodeRef root, double trav, double isect) {
    TreeStats s;
    if (root == kEmptyRef) return s;
    if (is_leaf(root)) {
      stats(root, 1.0, 1, trav, isect, s);
      return s;
    }
    double area = node_box(*ref_ptr<Node>(root)).surface_area();
    stats(root, area, 1, trav, isect, s);
    if (area > 0) {
      s.sah_cost /= area;
      s.pack_sah_cost /= area;
    }
    return s;
  }

  static size_t block_bytes(NodeRef ref) {
    if (is_leaf(ref)) return whole_lines(leaf_bytes(*leaf_header(ref), kCompact));
    return whole_lines(sizeof(Node));
  }

  static size_t total_bytes(NodeRef ref) {
    size_t bytes = block_bytes(ref);
    if (!is_leaf(ref)) {
      const Node& n = *ref_ptr<Node>(ref);
      for (int i = 0; i < N; ++i) {
        if (n.child[i] != kEmptyRef) bytes += total_bytes(n.child[i]);
      }
    }
    return bytes;
  }

  static NodeRef place(NodeRef ref, char* base, size_t& offset) {
    char* dst = base + offset;
    offset += block_bytes(ref);
    if (is_leaf(ref)) {
      std::memcpy(dst, ref_ptr<const char>(ref), leaf_bytes(*leaf_header(ref), kCompact));
      return make_leaf_ref(dst, leaf_code(ref));
    }
    std::memcpy(dst, ref_ptr<Node>(ref), sizeof(Node));
    return make_node_ref(dst);
  }

  // The children of a node are placed side by side (one sweep of the prefetcher covers the
  // siblings a ray tests next), then each child's subtree follows, depth first.
  static void place_children(Node* node, char* base, size_t& offset) {
    for (int i = 0; i < N; ++i) {
      if (node->child[i] != kEmptyRef) node->child[i] = place(node->child[i], base, offset);
    }
    for (int i = 0; i < N; ++i) {
      if (node->child[i] != kEmptyRef && !is_leaf(node->child[i]))
        place_children(ref_ptr<Node>(node->child[i]), base, offset);
    }
  }

  static NodeRef copy(NodeRef root, char* base, size_t& offset) {
    NodeRef placed = place(root, base, offset);
    if (!is_leaf(placed)) place_children(ref_ptr<Node>(placed), base, offset);
    return placed;
  }

  static void relayout(Tree& tree) {
    NodeRef root = tree.root();
    if (root == kEmptyRef || tree.relaid_out()) return;
    size_t bytes = total_bytes(root);
    char* buffer = static_cast<char*>(tree_alloc(bytes));
    size_t offset = 0;
    NodeRef new_root = copy(root, buffer, offset);
    tree.adopt_buffer(buffer, bytes, new_root);
  }
};

template <template <int, bool> class W, class F>
auto dispatch(const TreeShape& shape, F&& f) {
  switch (shape.width * 2 + (shape.compact ? 1 : 0)) {
    case 4:
      return f(W<2, false>{});
    case 5:
      return f(W<2, true>{});
    case 8:
      return f(W<4, false>{});
    case 9:
      return f(W<4, true>{});
    case 17:
      return f(W<8, true>{});
    default:
      return f(W<8, false>{});
  }
}

}  // namespace

TreeStats measure_tree(const Tree& tree, double trav_cost, double int_cost) {
  return dispatch<Walker>(
      tree.shape(), [&](auto w) { return decltype(w)::measure(tree.root(), trav_cost, int_cost); });
}

void relayout_depth_first(Tree& tree) {
  dispatch<Walker>(tree.shape(), [&](auto w) { decltype(w)::relayout(tree); });
}

}  // namespace tuneray::bvh
