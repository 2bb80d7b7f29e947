#include "accel/bvh_reinsert.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <sstream>
#include <utility>
#include <vector>

#include "accel/bvh_node_box.h"

namespace tuneray::bvh {

namespace {

// Each round takes this share of the inner nodes out, the least efficient first.
constexpr double kRoundShare = 0.10;
constexpr int kMaxRounds = 12;
// Rounds stop once one lowers the cost by less than this fraction.
constexpr double kMinGain = 0.002;

struct Node {
  BBox box;
  float area = 0.0f;
  int parent = -1;
  int child[2] = {-1, -1};
  NodeRef leaf = kEmptyRef;  // a leaf of the source tree, kept as it is

  bool is_leaf() const { return leaf != kEmptyRef; }
};

BBox merged(const BBox& a, const BBox& b) {
  BBox m = a;
  m.extend(b);
  return m;
}

template <bool kCompact>
class Reinserter {
 public:
  using Source = NodeOf<2, kCompact>;

  explicit Reinserter(const BoxMeasure& measure = {}) : measure_(measure) {}

  // False if the tree is not a proper binary tree (a node with an empty slot).
  bool load(NodeRef root_ref) {
    BBox root_box;
    const Source& r = *ref_ptr<Source>(root_ref);
    for (int i = 0; i < 2; ++i) {
      if (r.child[i] == kEmptyRef) return false;
      root_box.extend(child_box<2, kCompact>(r, i));
    }
    root_ = load(root_ref, root_box, -1);
    return root_ >= 0;
  }

  double cost() const {
    double sum = 0.0;
    for (const Node& n : nodes_)
      if (!n.is_leaf()) sum += n.area;
    return sum / nodes_[root_].area;
  }

  // One round: the share of inner nodes with the largest inefficiency are taken out, each with
  // its parent, and their two children put back where they cost least. Returns the moves made.
  size_t round() {
    std::vector<std::pair<float, int>> candidates;
    for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
      const Node& n = nodes_[i];
      if (n.is_leaf() || n.parent < 0) continue;
      candidates.push_back({inefficiency(n), i});
    }
    const size_t take = std::max<size_t>(1, static_cast<size_t>(candidates.size() * kRoundShare));
    if (candidates.size() > take) {
      std::nth_element(candidates.begin(), candidates.begin() + take, candidates.end(),
                       [](const auto& a, const auto& b) { return a.first > b.first; });
      candidates.resize(take);
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    size_t moves = 0;
    for (const auto& [measure, index] : candidates) {
      // Earlier moves may have made the candidate the root; it still has two children.
      if (nodes_[index].parent < 0) continue;
      move_children(index);
      ++moves;
    }
    return moves;
  }

  int depth() const { return depth_below(root_); }

  // Writes the inner nodes depth first into one buffer and hands it to the tree.
  void store(Tree& tree) {
    size_t inner = 0;
    for (const Node& n : nodes_) inner += n.is_leaf() ? 0 : 1;
    const size_t stride = whole_lines(sizeof(Source));
    char* buffer = static_cast<char*>(std::aligned_alloc(kCacheLine, inner * stride));
    if (!buffer) throw std::bad_alloc();
    base_ = buffer;
    stride_ = stride;
    used_ = 0;
    const NodeRef root = write(root_);
    tree.adopt_inner_nodes(buffer, used_ * stride, root);
  }

 private:
  int load(NodeRef ref, const BBox& box, int parent) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    nodes_[index].box = box;
    nodes_[index].area = measure_(box);
    nodes_[index].parent = parent;
    if (is_leaf(ref)) {
      nodes_[index].leaf = ref;
      return index;
    }
    const Source& s = *ref_ptr<Source>(ref);
    for (int i = 0; i < 2; ++i) {
      if (s.child[i] == kEmptyRef) return -1;
      const int c = load(s.child[i], child_box<2, kCompact>(s, i), index);
      if (c < 0) return -1;
      nodes_[index].child[i] = c;
    }
    return index;
  }

  // Bittner et al.'s combined measure: a large box, much larger than its children's together
  // and than its smaller child's, is where the builder's split went worst.
  float inefficiency(const Node& n) const {
    constexpr float kTiny = 1e-20f;
    const float a0 = nodes_[n.child[0]].area, a1 = nodes_[n.child[1]].area;
    const float sum = std::max(a0 + a1, kTiny), least = std::max(std::min(a0, a1), kTiny);
    return n.area * (n.area / sum) * (n.area / least);
  }

  int sibling(int index) const {
    const Node& p = nodes_[nodes_[index].parent];
    return p.child[0] == index ? p.child[1] : p.child[0];
  }

  void replace_child(int parent, int old_child, int new_child) {
    if (parent < 0) {
      root_ = new_child;
    } else {
      Node& p = nodes_[parent];
      p.child[p.child[0] == old_child ? 0 : 1] = new_child;
    }
    nodes_[new_child].parent = parent;
  }

  // Recomputes the boxes from `index` up to the root.
  void refit(int index) {
    for (; index >= 0; index = nodes_[index].parent) {
      Node& n = nodes_[index];
      n.box = merged(nodes_[n.child[0]].box, nodes_[n.child[1]].box);
      n.area = measure_(n.box);
    }
  }

  // Takes `index` and its parent out of the tree (the sibling takes the parent's place) and
  // puts the two children back, the larger first, each under one of the two freed nodes.
  void move_children(int index) {
    const int parent = nodes_[index].parent;
    const int grand = nodes_[parent].parent;
    const int other = sibling(index);
    replace_child(grand, parent, other);
    if (grand >= 0) refit(grand);
    int a = nodes_[index].child[0], b = nodes_[index].child[1];
    if (nodes_[a].area < nodes_[b].area) std::swap(a, b);
    insert(a, index);
    insert(b, parent);
  }

  // Puts subtree `x` beside the node where the summed inner area grows least (branch and bound
  // over the tree, cheapest induced cost first), under the free node `free_node`.
  void insert(int x, int free_node) {
    const BBox& xbox = nodes_[x].box;
    const float xarea = nodes_[x].area;
    float best_cost = std::numeric_limits<float>::infinity();
    int best = root_;
    queue_.clear();
    queue_.push_back({0.0f, root_});
    const auto later = [](const Entry& l, const Entry& r) { return l.induced > r.induced; };
    while (!queue_.empty()) {
      std::pop_heap(queue_.begin(), queue_.end(), later);
      const Entry e = queue_.back();
      queue_.pop_back();
      if (e.induced + xarea >= best_cost) break;
      const Node& n = nodes_[e.node];
      const float direct = measure_(merged(n.box, xbox));
      const float cost = e.induced + direct;
      if (cost < best_cost) {
        best_cost = cost;
        best = e.node;
      }
      if (n.is_leaf()) continue;
      const float induced = cost - n.area;
      if (induced + xarea >= best_cost) continue;
      for (int c : n.child) {
        queue_.push_back({induced, c});
        std::push_heap(queue_.begin(), queue_.end(), later);
      }
    }
    const int above = nodes_[best].parent;
    replace_child(above, best, free_node);
    Node& f = nodes_[free_node];
    f.child[0] = best;
    f.child[1] = x;
    nodes_[best].parent = free_node;
    nodes_[x].parent = free_node;
    refit(free_node);
  }

  int depth_below(int index) const {
    const Node& n = nodes_[index];
    if (n.is_leaf()) return 0;
    return 1 + std::max(depth_below(n.child[0]), depth_below(n.child[1]));
  }

  NodeRef write(int index) {
    const Node& n = nodes_[index];
    if (n.is_leaf()) return n.leaf;
    Source* out = new (base_ + used_++ * stride_) Source;
    clear_node<2, kCompact>(*out);
    const BBox boxes[2] = {nodes_[n.child[0]].box, nodes_[n.child[1]].box};
    set_child_boxes<2, kCompact>(*out, boxes, 2);
    for (int i = 0; i < 2; ++i) out->child[i] = write(n.child[i]);
    return make_node_ref(out);
  }

  struct Entry {
    float induced;
    int node;
  };

  BoxMeasure measure_;  // a box's price: its area, or weighted by a view's rays (ray_sample.h)
  std::vector<Node> nodes_;
  std::vector<Entry> queue_;
  int root_ = -1;
  char* base_ = nullptr;
  size_t stride_ = 0;
  size_t used_ = 0;
};

template <bool kCompact>
ReinsertStats run(Tree& tree, int max_depth, const BoxMeasure& measure) {
  ReinsertStats stats;
  stats.kept_original = true;
  stats.weighted = measure.weighted();
  Reinserter<kCompact> r(measure);
  if (!r.load(tree.root())) return stats;
  stats.cost_before = r.cost();
  double cost = stats.cost_before;
  bool changed = false;
  // A round is greedy (each child goes where it costs least with the other still out), so it
  // can end dearer or deeper than it began: then the tree before it is kept.
  Reinserter<kCompact> before;
  while (stats.rounds < kMaxRounds) {
    before = r;
    const size_t moves = r.round();
    ++stats.rounds;
    const double next = r.cost();
    if (next >= cost || r.depth() > max_depth) {
      r = std::move(before);
      break;
    }
    stats.moves += moves;
    changed = true;
    const bool small_gain = next > cost * (1.0 - kMinGain);
    cost = next;
    if (small_gain) break;
  }
  stats.cost_after = cost;
  stats.depth = r.depth();
  if (!changed) return stats;
  r.store(tree);
  stats.kept_original = false;
  return stats;
}

}  // namespace

ReinsertStats reinsert_subtrees(Tree& tree, int max_depth, const BoxMeasure& measure) {
  const NodeRef root = tree.root();
  if (root == kEmptyRef || is_leaf(root) || tree.shape().width != 2 || tree.collapsed()) {
    ReinsertStats stats;
    stats.kept_original = true;
    return stats;
  }
  return tree.shape().compact ? run<true>(tree, max_depth, measure)
                              : run<false>(tree, max_depth, measure);
}

std::string describe(const ReinsertStats& stats) {
  std::ostringstream out;
  if (stats.rounds == 0) return "reinsertion: nothing to do";
  out.precision(4);
  out << "reinsertion: " << (stats.weighted ? "ray-weighted cost " : "SAH ") << stats.cost_before
      << " -> " << stats.cost_after << " in " << stats.rounds << " rounds, " << stats.moves
      << " moves";
  if (stats.kept_original)
    out << ", tree kept as built";
  else
    out << ", depth " << stats.depth;
  return out.str();
}

}  // namespace tuneray::bvh
