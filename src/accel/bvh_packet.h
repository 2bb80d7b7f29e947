// Packet traversal of the tuned BVH for coherent batches (camera rays): groups of 8 rays that
// share a direction octant traverse the tree together (one node load, each child box tested
// against all 8 rays in one AVX2 pass, each ray keeping its own entry distance on the stack), and
// a packet that thins out hands its remaining rays to the single-ray traversal (hybrid
// traversal, as Embree's packet intersectors do). Leaves reached by several rays are tested with
// SIMD over the rays, with each lane doing the operations of the single-ray test in the same
// order, and equal distances go to the lower triangle index on both paths, so a ray finds the
// same hit bit for bit whichever path traced it.
//
// Measured (docs/bvh.md): a gain on camera rays only. Scattered bounce rays and shadow rays stay
// on the single-ray kernels, where packets were no faster.
#pragma once

#include <cstddef>

#include "accel/bvh_traverse.h"

namespace tuneray::bvh {

// Closest hits of `count` rays; `single` are the tree's single-ray kernels (for the rays of
// packets that thin out and of octants too small for a packet).
using IntersectBatchKernel = void (*)(const TraversalContext&, const Kernels& single,
                                      const Ray* rays, size_t count, Hit* hits);

// The packet kernel for a tree of this shape, or nullptr where there is none (compact or robust
// layouts, and width 2, whose nodes are too narrow to amortise a packet's box tests).
IntersectBatchKernel select_coherent_batch_kernel(const TreeShape& shape);

}  // namespace tuneray::bvh
