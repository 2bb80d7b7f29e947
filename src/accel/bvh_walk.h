// Whole-tree walks over a built tuned BVH: statistics (for BuildStats) and the depth-first
// relayout that gives `static=1` its meaning.
#pragma once

#include <cstddef>

#include "accel/bvh_tree.h"

namespace tuneray::bvh {

struct TreeStats {
  size_t node_count = 0;
  size_t leaf_count = 0;
  size_t references = 0;  // triangle references in leaves
  size_t max_leaf_size = 0;
  int depth = 0;        // levels of inner nodes + the leaf level
  double sah_cost = 0;  // trav * sum A(node)/A(root) + int * sum A(leaf)/A(root) * refs
  // The same with a leaf's triangles counted in packs of 4, as the fast leaves test them (what
  // the collapse minimises).
  double pack_sah_cost = 0;
  size_t node_bytes = 0;
  size_t leaf_bytes = 0;
  // Fast leaves whose reference does not carry their header's pack count (always 0 for a
  // correct tree: the traversal reads the count from the reference).
  size_t leaf_code_mismatches = 0;
};

TreeStats measure_tree(const Tree& tree, double trav_cost, double int_cost);

// Copies nodes and leaves depth-first into one contiguous allocation (the children of a node
// side by side, followed by the first child's subtree, then the second's, ...) and frees the
// Embree-held tree.
void relayout_depth_first(Tree& tree);

}  // namespace tuneray::bvh
