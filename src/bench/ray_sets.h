// The fixed ray sets the traversal matrix times both accelerators on.
#pragma once

#include <string>
#include <vector>

#include "accel/accel.h"
#include "scene/scene.h"

namespace tuneray {

struct RaySet {
  std::string name;
  bool shadow = false;
  std::vector<Ray> rays;
};

// Primary rays through the first camera in 8x8 pixel tiles (coherent order); bounce rays from
// their hits with cosine-distributed directions; shadow rays from the hits to points on emissive
// triangles, point lights, or (neither) a point above the scene. About `count` rays each,
// deterministic; `reference` finds the hits.
std::vector<RaySet> make_ray_sets(const Scene& scene, const Accel& reference, size_t count);

// Seconds for one pass over the set, all threads: wall time, or the CPU time of all threads
// (which other processes on a shared machine do not inflate by taking turns on the cores).
double trace_seconds(const Accel& accel, const RaySet& set, bool cpu_time = false);

}  // namespace tuneray
