// Builds the tuned BVH with Embree's rtcBuildBVH and our own node/leaf callbacks.
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/bvh_config.h"
#include "accel/bvh_tree.h"
#include "accel/embree_device.h"

namespace tuneray::bvh {

// quality=high gives Embree room for this many references per triangle (spatial splits append
// duplicated references; Embree stops splitting when the array is full).
inline constexpr double kSpatialSplitCapacityFactor = 2.0;

// A triangle's three vertices side by side (x, y, z, unused), so that splitPrimitive, which
// Embree calls for every bin boundary a fragment spans during spatial binning, loads them with
// three aligned vector loads and no index indirection.
struct alignas(16) SplitTriangle {
  float v[3][4];
};

// The splitPrimitive callback of quality=high: clips `tri` at `position` along `dim` and writes
// the boxes of the two halves, each intersected with `prim`'s box (the primitive may already be
// a fragment of an earlier split); left ends at `position`, right starts there. Crossing points
// are padded outward by a few ulps, so each box contains the exact part of the triangle within
// `prim`'s box on its side despite rounding.
void split_bounds(const SplitTriangle& tri, const RTCBuildPrimitive& prim, unsigned int dim,
                  float position, RTCBounds& left, RTCBounds& right);

// Per-geometry data of the builds, kept across builds of the same geometry:
// - the build primitives (one box per triangle), kept pristine because rtcBuildBVH reorders and
//   extends its array in place: every build copies them into the working array first;
// - for quality=high, the vertices of every triangle (SplitTriangle), made at the first high
//   build (48 bytes a triangle).
// Geometry is recognised by its array pointers and sizes (as the accelerators share the arrays,
// moved or edited vertices need a new GeometryView or a fresh cache).
class PrimitiveCache {
 public:
  // Recomputes the boxes when the geometry differs from the cached one, and the split vertices
  // when `split_vertices` is set and they are missing.
  void prepare(const GeometryView& geometry, bool split_vertices = false);
  // The working array, restored from the pristine copy, with `capacity` >= count entries. A
  // medium build after a high one reuses the larger array (no reallocation when the tuner
  // alternates qualities).
  RTCBuildPrimitive* restore(size_t capacity);
  size_t count() const { return pristine_.size(); }
  // The vertices for splitPrimitive (empty unless prepared with split_vertices).
  const SplitTriangle* split_triangles() const { return split_.empty() ? nullptr : split_.data(); }

 private:
  const void* positions_ = nullptr;
  const void* triangles_ = nullptr;
  size_t vertex_count_ = 0;
  std::vector<RTCBuildPrimitive> pristine_;
  std::unique_ptr<RTCBuildPrimitive[]> work_;  // uninitialised: restore() writes what it needs
  size_t work_capacity_ = 0;
  std::vector<SplitTriangle> split_;
};

struct BuildResult {
  size_t spatial_splits = 0;  // spatial splits Embree kept: each adds one reference
  size_t references = 0;      // triangle references in leaves (count + spatial_splits)
  size_t inner_nodes = 0;     // inner nodes Embree asked for (at least the tree's)
  std::string notes;
};

// Builds into `tree` (which is reset first). Throws BuildError when Embree refuses; the tree is
// then empty. `config` must be validated.
BuildResult build_tree(const GeometryView& geometry, const BvhConfig& config, EmbreeDevice& device,
                       PrimitiveCache& primitives, Tree& tree);

}  // namespace tuneray::bvh
