// Coherent batches (camera rays) of the tuned BVH as streams: up to 64 consecutive rays that
// share a direction octant traverse the tree together, as 8 packets of 8 (AVX2) or 4 packets of
// 16 (AVX-512). The batch is taken in its own order, in runs of one octant (no sort: a camera's
// rays change octant only where the view crosses an axis, and the wavefront scheduler hands them
// over in 8×8 pixel blocks); a packet is read from the wavefront's planes as they are, or from
// records, 8 rows at a time, transposed. At each node a frustum of the
// stream's rays (per axis the range of their inverse directions and origin terms, padded far
// above the roundings) culls the children no ray can enter, for all of them at once; each child
// it keeps is tested against each packet's rays in one SIMD pass, and the stream goes on nearest
// child first. Rays that thin out go on one by one in the single-ray traversal (hybrid
// traversal, as Embree's coherent streams do). Leaves reached by several rays of a packet are
// tested with SIMD over the rays, each lane doing the operations of the single-ray test in the
// same order, and equal distances go to the lower triangle index on both paths, so a ray finds
// the same hit bit for bit whichever path traced it.
//
// Measured (docs/bvh.md): a gain on camera rays only. Scattered bounce rays and shadow rays stay
// on the single-ray kernels and the shadow streams (bvh_stream.h).
#pragma once

#include <cstddef>

#include "accel/bvh_traverse.h"
#include "accel/ray_planes.h"

namespace tuneray::bvh {

// Closest hits of `count` rays; `single` are the tree's single-ray kernels (for the rays of
// streams that thin out and of octants too small for a packet).
using IntersectBatchKernel = void (*)(const TraversalContext&, const Kernels& single,
                                      const Ray* rays, size_t count, Hit* hits);

// The stream kernel for a tree of this shape, or nullptr where there is none (compact or robust
// layouts, and width 2, whose nodes are too narrow to amortise a packet's box tests).
IntersectBatchKernel select_coherent_batch_kernel(const TreeShape& shape);

// The same for rays as planes (the wavefront's camera rays), each packet read from the planes:
// no copy into records and back into rows. The same hits as the batch kernel's, bit for bit.
using IntersectPlanesKernel = void (*)(const TraversalContext&, const Kernels& single,
                                       const RayPlanes& rays, Hit* hits);
IntersectPlanesKernel select_coherent_planes_kernel(const TreeShape& shape);

}  // namespace tuneray::bvh
