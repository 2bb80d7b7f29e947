// The offline side of the viewer's agreement tests: the same camera rendered the way `render`
// does (tiles, PCG samples, a fixed number of samples per pixel), as the window would show it.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace tuneray::testing {

// 8-bit sRGB bytes (rows top to bottom) of `camera` at `spp`, native Embree, 3 bounces.
std::vector<uint8_t> offline_display_bytes(const Scene& scene, const CameraDesc& camera, int width,
                                           int height, uint32_t spp);

// Root mean square difference of two byte images in display units ([0, 1] per channel).
double display_rmse(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

}  // namespace tuneray::testing
