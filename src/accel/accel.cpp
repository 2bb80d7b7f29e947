#include "accel/accel.h"

#include <vector>

namespace tuneray {

void Accel::intersect_batch(std::span<const Ray> rays, std::span<Hit> hits, RayCoherence) const {
  for (size_t i = 0; i < rays.size(); ++i) {
    hits[i] = Hit{};
    intersect(rays[i], hits[i]);
  }
}

void Accel::occluded_batch(std::span<const Ray> rays, std::span<uint8_t> occluded_out) const {
  for (size_t i = 0; i < rays.size(); ++i) occluded_out[i] = occluded(rays[i]) ? 1 : 0;
}

void Accel::intersect_planes(const RayPlanes& rays, std::span<Hit> hits,
                             RayCoherence coherence) const {
  thread_local std::vector<Ray> records;
  records.resize(rays.size);
  rays_from_planes(rays, records);
  intersect_batch(records, hits, coherence);
}

}  // namespace tuneray
