// `reinsert=1`: the binary tree Embree's builder made is improved before it is collapsed, by
// moving subtrees to where they lower its SAH cost (Bittner, Hapala and Havran, "Fast
// insertion-based optimization of bounding volume hierarchies", CGF 2013).
//
// A top-down binned builder decides each split once, from the centroids of what it sees at that
// level, and never revisits it: large or long triangles end deep in subtrees whose boxes they
// stretch. Reinsertion takes the nodes whose boxes are largest relative to their children's out
// of the tree and puts their children back where the summed area of all inner nodes (the SAH
// cost, the leaves being unchanged) grows least. Leaves stay as built: the same triangles, the
// same payloads, so every ray finds the same hits.
#pragma once

#include <cstddef>
#include <string>

#include "accel/bvh_tree.h"
#include "accel/ray_sample.h"

namespace tuneray::bvh {

struct ReinsertStats {
  double cost_before = 0.0;  // summed measure (surface area) of the inner nodes over the root's
  double cost_after = 0.0;
  int rounds = 0;
  size_t moves = 0;            // subtrees taken out and put back (possibly where they were)
  int depth = 0;               // of the tree kept
  bool kept_original = false;  // the result was deeper than `max_depth`, or nothing to do
  bool weighted = false;       // boxes priced by a view's rays (ray_sample.h), not by area
};

// Optimizes a binary tree (width 2, either layout) in place: its inner nodes are rewritten into
// one buffer the tree owns, its leaves stay where they are. Trees of other widths, or with a
// leaf for a root, are left as they are. A result deeper than `max_depth` (the traversal's
// stack is sized by it) is discarded and the tree kept as built. `measure` replaces the boxes'
// surface area in the cost (ray_sample.h); its default is the area.
ReinsertStats reinsert_subtrees(Tree& tree, int max_depth, const BoxMeasure& measure = {});

std::string describe(const ReinsertStats& stats);

}  // namespace tuneray::bvh
