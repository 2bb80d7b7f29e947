// Traversal kernels of the tuned BVH: one template over width N (2 scalar, 4 SSE, 8 AVX2),
// layout (fast / compact), triangle test (fast / watertight) and query (closest / any hit).
// Hit children are visited nearest first (sorted by entry distance); farther ones go on a stack
// with their distance so a closest-hit query skips them once a nearer hit is known.
#pragma once

#include <cstdint>

#include "accel/accel.h"
#include "accel/bvh_layout.h"
#include "accel/bvh_tree.h"

namespace tuneray {
struct Triangle;
}

namespace tuneray::bvh {

struct TraversalContext {
  NodeRef root = kEmptyRef;
  const Vec3f* positions = nullptr;
  const Triangle* triangles = nullptr;
};

using IntersectKernel = bool (*)(const TraversalContext&, const Ray&, Hit&);
using OccludedKernel = bool (*)(const TraversalContext&, const Ray&);

struct Kernels {
  IntersectKernel intersect = nullptr;
  OccludedKernel occluded = nullptr;
};

Kernels select_kernels(const TreeShape& shape);

}  // namespace tuneray::bvh
