#include "accel/accel.h"

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

}  // namespace tuneray
