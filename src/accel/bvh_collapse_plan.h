// The SAH-optimal collapse of a 2- or 4-wide tree into 8-wide nodes (`optimal_collapse=1`),
// after Ylitie, Karras and Laine, "Efficient Incoherent Ray Traversal on GPUs Through Compressed
// Wide BVHs" (HPG 2017): a bottom-up dynamic programme finds, for every source node and every
// k <= 8, the least cost of its subtree standing as at most k children of a wide node, each a
// leaf or the root of a wide node; the collapse then follows the choices from the root down.
// The greedy rule (open the largest child that fits) decides node by node and never gives a
// slot of one child's to another's subtree; the programme does.
//
// Costs are those of the greedy collapse's leaf pricing (bvh_collapse.h): a wide node costs the
// measure of its box (one visit tests all its children), a leaf its measure times `pack_cost` per
// pack of 4 triangles; the measure is the box's area, or ray_sample.h's weighted by a view's
// rays. A subtree of at most `flatten_limit` triangles may become one leaf (0: leaves stay as
// built).
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "accel/bvh_config.h"
#include "accel/bvh_node_box.h"
#include "accel/bvh_tree.h"
#include "accel/ray_sample.h"

namespace tuneray::bvh {

// What testing `triangles` in packs of 4 costs at `pack_cost` a pack (a node visit costing 1):
// the leaf price of both collapses.
inline float packs_price(float pack_cost, int triangles) {
  return pack_cost * static_cast<float>((triangles + 3) / 4);
}

template <int N, bool kCompact>
class CollapsePlan {
 public:
  static constexpr int kWide = BvhConfig::kCollapsedWidth;
  using Source = NodeOf<N, kCompact>;

  // `inner_nodes` (at least the source tree's inner node count) sizes the table once.
  CollapsePlan(NodeRef root, size_t inner_nodes, int flatten_limit, float pack_cost,
               const BoxMeasure& measure = {})
      : flatten_limit_(flatten_limit), pack_cost_(pack_cost), measure_(measure) {
    nodes_.reserve(inner_nodes * N + 1);
    int triangles = 0;
    plan(root, 0.0f, triangles);
  }

  // The plan index of the root (of the tree the plan was made for) and of child `i` of the
  // source node at `index` (-1 where the slot is empty).
  static int root() { return 0; }
  int child(int index, int i) const { return nodes_[index].child[i]; }

  // Whether the source node at `index`, standing as one child of a wide node, is best one leaf
  // (always, for a leaf of the build).
  bool as_leaf(int index) const { return nodes_[index].as_leaf; }

  // The planned cost of the subtree at `index` given k slots (k = 8: as the root).
  float cost(int index, int k) const { return nodes_[index].cost[k]; }

  // Calls emit(parent, i, child_index) for each child a wide node made for the source inner node
  // at `index` takes: source child `i` of source node `parent`, or, where the plan spreads a
  // child over several slots, that child's own children in turn.
  template <class Emit>
  void spread(int index, Emit&& emit) const {
    spread(index, kWide, emit);
  }

 private:
  struct Node {
    NodeRef ref = kEmptyRef;
    int child[N];
    float cost[kWide + 1];       // cost[k]: the subtree as at most k slots (cost[0] unused)
    uint16_t spreads = 0;        // bit k: cost[k] spreads over the children, not one slot
    uint8_t take[N][kWide + 1];  // slots child j takes when the first j + 1 children share k
    bool as_leaf = false;
  };

  static constexpr float kNever = std::numeric_limits<float>::infinity();

  float packs_cost(int triangles) const { return packs_price(pack_cost_, triangles); }

  // Fills nodes_ for the subtree at `ref` (box area `area`), children first; returns its index
  // and the number of triangles below it (capped at flatten_limit_ + 1).
  int plan(NodeRef ref, float area, int& triangles) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_[index].ref = ref;
    if (is_leaf(ref)) {
      triangles = static_cast<int>(leaf_header(ref)->prim_count);
      Node& p = nodes_[index];
      std::fill(p.child, p.child + N, -1);
      p.as_leaf = true;
      std::fill(p.cost, p.cost + kWide + 1, area * packs_cost(triangles));
      return index;
    }
    const Source& source = *ref_ptr<Source>(ref);
    int child[N];
    triangles = 0;
    for (int i = 0; i < N; ++i) {
      child[i] = -1;
      if (source.child[i] == kEmptyRef) continue;
      int below = 0;
      child[i] = plan(source.child[i], measure_(child_box<N, kCompact>(source, i)), below);
      triangles = std::min(triangles + below, flatten_limit_ + 1);
    }
    Node& p = nodes_[index];  // the children's emplace_back may have moved it
    std::copy(child, child + N, p.child);
    // A knapsack over the children: shared[k], the least cost of the children so far sharing
    // at most k slots, each child at least one. The children's costs never rise with more
    // slots, so neither does shared[].
    float shared[kWide + 1];
    std::fill(shared, shared + kWide + 1, kNever);
    shared[0] = 0.0f;
    int seen = 0;
    for (int j = 0; j < N; ++j) {
      std::fill(p.take[j], p.take[j] + kWide + 1, uint8_t{0});
      if (child[j] < 0) continue;
      const Node& c = nodes_[child[j]];
      float next[kWide + 1];
      for (int k = 0; k <= kWide; ++k) {
        next[k] = kNever;
        for (int a = 1; a <= k - seen; ++a) {
          const float cost = shared[k - a] + c.cost[a];
          if (cost < next[k]) {
            next[k] = cost;
            p.take[j][k] = static_cast<uint8_t>(a);
          }
        }
      }
      std::copy(next, next + kWide + 1, shared);
      ++seen;
    }
    const float as_node = area + shared[kWide];
    const float as_leaf = triangles <= flatten_limit_ ? area * packs_cost(triangles) : kNever;
    p.as_leaf = as_leaf <= as_node;
    const float one_slot = std::min(as_leaf, as_node);
    for (int k = 1; k <= kWide; ++k) {
      const bool spreads = shared[k] < one_slot;
      p.cost[k] = spreads ? shared[k] : one_slot;
      if (spreads) p.spreads |= static_cast<uint16_t>(1u << k);
    }
    return index;
  }

  template <class Emit>
  void spread(int index, int k, Emit& emit) const {
    const Node& p = nodes_[index];
    int share[N];
    for (int j = N - 1; j >= 0; --j) {
      share[j] = p.child[j] < 0 ? 0 : p.take[j][k];
      k -= share[j];
    }
    const Source& source = *ref_ptr<Source>(p.ref);
    for (int j = 0; j < N; ++j) {
      const int c = p.child[j];
      if (c < 0) continue;
      if (nodes_[c].spreads & (1u << share[j]))
        spread(c, share[j], emit);
      else
        emit(source, j, c);
    }
  }

  int flatten_limit_;
  float pack_cost_;
  BoxMeasure measure_;  // a box's price (its area unless weighted by a view's rays)
  std::vector<Node> nodes_;
};

}  // namespace tuneray::bvh
