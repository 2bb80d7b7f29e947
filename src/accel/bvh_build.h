// Builds the tuned BVH with Embree's rtcBuildBVH and our own node/leaf callbacks.
#pragma once

#include <embree3/rtcore.h>

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

// The build primitives (one box per triangle), kept pristine because rtcBuildBVH reorders and
// extends its array in place: every build copies them into the working array first.
class PrimitiveCache {
 public:
  // Recomputes the boxes when the geometry differs from the cached one.
  void prepare(const GeometryView& geometry);
  // The working array, restored from the pristine copy, with `capacity` >= count entries.
  RTCBuildPrimitive* restore(size_t capacity);
  size_t count() const { return pristine_.size(); }

 private:
  const void* positions_ = nullptr;
  const void* triangles_ = nullptr;
  size_t vertex_count_ = 0;
  std::vector<RTCBuildPrimitive> pristine_;
  std::vector<RTCBuildPrimitive> work_;
};

struct BuildResult {
  size_t spatial_splits = 0;  // splitPrimitive calls that produced two boxes
  size_t references = 0;      // triangle references in leaves (> count with spatial splits)
  std::string notes;
};

// Builds into `tree` (which is reset first). Throws BuildError when Embree refuses; the tree is
// then empty. `config` must be validated.
BuildResult build_tree(const GeometryView& geometry, const BvhConfig& config, EmbreeDevice& device,
                       PrimitiveCache& primitives, Tree& tree);

}  // namespace tuneray::bvh
