// `collapse=1`: a tree built with branching 2 or 4 is stored and traversed as an 8-wide tree.
//
// Embree's builder with branching 8 and the same other parameters makes a different tree: it
// stops at smaller leaves (conference, Embree's defaults: 1.25 triangles a leaf at branching 8,
// 2.4 at branching 2), and our leaves test triangles in packs of 4. Collapsing the binary tree
// keeps its fuller leaves and gives the traversal 8-wide nodes.
#pragma once

#include "accel/bvh_config.h"
#include "accel/bvh_tree.h"
#include "accel/ray_sample.h"

namespace tuneray::bvh {

// Merges inner nodes into 8-wide nodes, greedily: of the children of a node under construction,
// the inner child with the largest surface area whose children still fit is replaced by them,
// until none fits (the rule Embree's own wide builders split by). The wide nodes are written
// depth first into one allocation; the leaves stay where the build put them, unchanged, so
// every ray finds the same triangles (static=1 then copies the whole tree into one allocation).
// `max_inner_nodes` is at least the source tree's inner node count (BuildResult::inner_nodes).
// A tree already 8 wide, a lone leaf or an already collapsed tree is left as it is.
//
// With `merge_leaves_up_to` > 1 (fast layout only), leaves are priced as our leaves test them, in
// packs of 4 (the build's SAH priced them triangle by triangle and, with Embree's default blocks
// of one, made leaves of 1-2 triangles under deep subtrees): a source inner node with at most that
// many triangles becomes one leaf where the SAH with a node visit costing 1 and a leaf
// `pack_cost` per pack says it is no dearer than its best subtree (at 1, Embree's SAH with blocks
// of 4, as its BVH8 builds for its own packs), and leaf children of a wide node merge pairwise
// while that lowers their summed cost. The tuned BVH passes its configuration's
// int_cost / trav_cost, so the two costs the tuner sets for the build steer the leaves too: on
// Embree's 34-triangle Cornell box 1:1 made one node of three leaves of 11-12 triangles. Such
// leaves are written into a buffer of the tree's own, the others stay. Every triangle keeps its
// references, so rays find the same hits. (stanford-bunny, Embree's defaults: 29,423 wide nodes and
// 82,428 leaves of 1.75 triangles become 7,914 and 28,409 of 5.07.)
//
// With `optimal`, which children each wide node takes is not decided by the greedy rule but by
// the SAH-optimal plan of bvh_collapse_plan.h under the same prices (sibling leaves merge as
// above afterwards; the slots they free stay free, where the plan wanted no further child).
//
// Every price above is a box's surface area times a constant; `measure` replaces the area
// (accel/ray_sample.h: weighted by where a view's rays go).
void collapse_to_wide(Tree& tree, size_t max_inner_nodes, int merge_leaves_up_to = 0,
                      float pack_cost = 1.0f, bool optimal = false, const BoxMeasure& measure = {});

}  // namespace tuneray::bvh
