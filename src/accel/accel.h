// The acceleration-structure interface. The integrator calls only this; which backend answers
// (Embree's native BVH or our tuned BVH) is chosen by the factory. A rebuild is requested with
// build() and its time is measured by the backend and reported separately from rendering.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>

#include "accel/ray_planes.h"
#include "math/ray.h"
#include "math/vec.h"

namespace tuneray {

struct Triangle;

// What a backend builds over: world-space positions and triangles. The arrays must outlive the
// accelerator (backends share them, they do not copy).
struct GeometryView {
  const Vec3f* positions = nullptr;
  size_t vertex_count = 0;
  const Triangle* triangles = nullptr;
  size_t triangle_count = 0;
};

struct BuildStats {
  double build_ms = 0;      // wall time of the build itself
  size_t memory_bytes = 0;  // nodes + leaves (+ primitive data owned by the backend)
  size_t node_count = 0;    // inner nodes (0 when the backend cannot tell)
  size_t leaf_count = 0;
  int depth = 0;
  double sah_cost = 0;  // 0 when unknown
  std::string notes;    // e.g. "quality=high fell back to medium"
};

// A build the backend refused (e.g. Embree's "depth limit reached"). Callers such as the tuner
// treat it as an infinitely slow configuration; the accelerator is left empty, never corrupt.
class BuildError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How alike neighbouring rays of a batch are. Coherent: they leave from about one point in
// about one direction, as camera rays in pixel order do, so they visit the same nodes.
enum class RayCoherence { kIncoherent, kCoherent };

class Accel {
 public:
  virtual ~Accel() = default;

  virtual std::string name() const = 0;
  // The backend's current settings as `key=value,...`.
  virtual std::string describe() const = 0;

  // (Re)builds over `geometry`. Throws BuildError on a refused build.
  virtual BuildStats build(const GeometryView& geometry) = 0;

  // Closest hit in [ray.tnear, ray.tfar]. Returns hit.valid(). A negative or NaN tnear reads
  // as 0 (Embree requires tnear >= 0; both backends clamp it, in every entry point).
  virtual bool intersect(const Ray& ray, Hit& hit) const = 0;
  // Any hit in [ray.tnear, ray.tfar] (shadow rays).
  virtual bool occluded(const Ray& ray) const = 0;

  // Batches, for the wavefront mode. The default loops over the single-ray calls; backends
  // override with packet/stream traversal. occluded[i] is 1 when ray i is blocked. A backend may
  // trace a coherent batch as packets; the hits are those of the single-ray calls either way.
  virtual void intersect_batch(std::span<const Ray> rays, std::span<Hit> hits,
                               RayCoherence coherence = RayCoherence::kIncoherent) const;
  virtual void occluded_batch(std::span<const Ray> rays, std::span<uint8_t> occluded) const;
  // intersect_batch on rays given as planes. The default copies them into Ray records first.
  virtual void intersect_planes(const RayPlanes& rays, std::span<Hit> hits,
                                RayCoherence coherence = RayCoherence::kIncoherent) const;
};

}  // namespace tuneray
