// The order in which the wavefront scheduler takes an image's pixels into its waves: bands of
// 8 rows, each cut into 8×8 blocks from left to right, the pixels of a block in Morton (Z)
// order. Consecutive pixels then lie close together on the image, so the camera rays that a
// batch kernel groups (runs of 64 within a direction octant, docs/bvh.md) span a square of
// the image instead of a one-pixel-high strip: a tight frustum for the tuned BVH's camera streams,
// and first hits close to each other for the shading and the bounce rays that follow.
// Scanline order made each run of 64 camera rays a 64×1 strip (32×1 at 2 spp).
#pragma once

#include <cstdint>
#include <vector>

namespace tuneray {

// Every pixel index y * width + x of the image exactly once, in the order above. Blocks cut by
// the image's right or bottom edge keep the Morton order of their pixels that exist;
// an image without pixels has none.
std::vector<uint32_t> wave_pixel_order(int width, int height);

}  // namespace tuneray
