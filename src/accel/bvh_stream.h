// Stream traversal of the tuned BVH for batches of any-hit queries (shadow rays), the way
// Embree's stream intersector traces incoherent occlusion rays: a batch is sorted into direction
// octants and up to 32 rays of one octant go down the tree together as a bit mask. A node's
// boxes are loaded once for the whole group and each ray in the group tests them with the
// single-ray box test; a child carries on with the rays that entered it. A ray stops at its
// first hit. Leaves are tested ray by ray with the single-ray leaf test. The rays need not be
// coherent: what the stream saves is one node fetch and one stack step per group instead of per
// ray, and the shared upper levels of the tree.
//
// Every ray gets the answer of the single-ray any-hit kernel: it enters the same boxes (same
// test, same operations) and tests the same leaves, and it is blocked exactly when one of those
// leaves holds a triangle it hits.
#pragma once

#include <cstddef>
#include <cstdint>

#include "accel/bvh_traverse.h"

namespace tuneray::bvh {

// Whether each of `count` rays is blocked (1) or not (0).
using OccludedBatchKernel = void (*)(const TraversalContext&, const Ray* rays, size_t count,
                                     uint8_t* occluded);

// The stream kernel for a tree of this shape, or nullptr where there is none (compact or robust
// layouts, and width 2): the caller then loops over the single-ray kernel.
OccludedBatchKernel select_occluded_batch_kernel(const TreeShape& shape);

}  // namespace tuneray::bvh
