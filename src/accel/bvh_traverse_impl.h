// The single-ray traversal of the tuned BVH (its AVX2 copy, tuneray::bvh::single, from
// bvh_traverse_kernel.inc) and the helpers that group a batch's rays by direction octant, shared
// by the single-ray kernels (bvh_traverse.cpp), the camera-ray streams (bvh_packet.cpp), which hand
// rays over to the single-ray traversal when a stream thins out and use its leaf tests so both give
// the same hits bit for bit, and the shadow streams (bvh_stream.cpp). Internal to src/accel.
#pragma once

#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>
#include <vector>

#include "accel/bvh_layout.h"
#include "accel/bvh_traverse.h"
#include "accel/bvh_triangle.h"
#include "accel/ray_planes.h"
#include "scene/scene.h"

// The AVX2 copy of the single-ray kernels (what runs on CPUs without AVX-512, and what the shadow
// streams of bvh_stream.cpp use everywhere).
namespace tuneray::bvh::single {
#include "accel/bvh_traverse_kernel.inc"
}  // namespace tuneray::bvh::single

namespace tuneray::bvh::detail {

// ---- batches: groups of rays of one direction octant, for the packet and stream kernels.

// Bit a set = the ray's direction is negative along axis a, by the sign test of
// make_traversal_ray (a -0 or tiny negative component counts as negative), so a group's shared
// near planes are the ones each of its rays would use alone. The sign bits come from one load
// (dir and tfar are the ray's second 16 bytes).
inline int ray_octant(const Ray& ray) {
  static_assert(offsetof(Ray, dir) + 4 * sizeof(float) <= sizeof(Ray), "dir and one float");
  return _mm_movemask_ps(_mm_loadu_ps(&ray.dir.x)) & 7;
}
// ray_octant of ray i of planes: the same sign bits.
inline int plane_octant(const RayPlanes& rays, size_t i) {
  return static_cast<int>((std::bit_cast<uint32_t>(rays.dir[0][i]) >> 31) |
                          (std::bit_cast<uint32_t>(rays.dir[1][i]) >> 31) << 1 |
                          (std::bit_cast<uint32_t>(rays.dir[2][i]) >> 31) << 2);
}

// A group's near planes come from its octant, never from one of its rays: a ray with a NaN
// direction (which enters no box) must not hand its rows to the others.
inline void near_rows_of_octant(int octant, int (&near_row)[3]) {
  for (int a = 0; a < 3; ++a) near_row[a] = (octant >> a) & 1 ? a + 3 : a;
}
inline void far_rows_of_octant(int octant, int (&far_row)[3]) {
  for (int a = 0; a < 3; ++a) far_row[a] = (octant >> a) & 1 ? a : a + 3;
}

// Sorts a batch into direction octants (as Embree's ray streams do) and calls
// `group(index, n, octant)` for each run of up to `size` rays of one octant, in batch order within
// the octant (`index` holds their batch positions), or `single(i)` for each ray of a run shorter
// than `min_size`, too thin to be worth a group.
template <class GroupFn, class SingleFn>
void for_each_octant_group(const Ray* rays, size_t count, int size, int min_size, GroupFn group,
                           SingleFn single) {
  thread_local std::vector<uint32_t> order;
  thread_local std::vector<uint8_t> octant_of;
  order.resize(count);
  octant_of.resize(count);
  size_t begin[9] = {};
  for (size_t i = 0; i < count; ++i) {
    octant_of[i] = static_cast<uint8_t>(ray_octant(rays[i]));
    ++begin[octant_of[i] + 1];
  }
  for (int o = 0; o < 8; ++o) begin[o + 1] += begin[o];
  size_t fill[8];
  std::copy(begin, begin + 8, fill);
  for (size_t i = 0; i < count; ++i) order[fill[octant_of[i]]++] = static_cast<uint32_t>(i);
  for (int o = 0; o < 8; ++o) {
    for (size_t first = begin[o]; first < begin[o + 1]; first += static_cast<size_t>(size)) {
      const int n =
          static_cast<int>(std::min<size_t>(static_cast<size_t>(size), begin[o + 1] - first));
      if (n < min_size) {
        for (int i = 0; i < n; ++i) single(order[first + i]);
      } else {
        group(&order[first], n, o);
      }
    }
  }
}

// The batch kernels (packets, streams) exist for the 4- and 8-wide fast, non-robust layouts only:
// the kernel of this tree's width, or nullptr, where the caller loops over single rays.
template <class Kernel>
Kernel batch_kernel_for(const TreeShape& shape, Kernel width8, Kernel width4) {
  if (shape.compact || shape.robust) return nullptr;
  if (shape.width == 8) return width8;
  if (shape.width == 4) return width4;
  return nullptr;
}

}  // namespace tuneray::bvh::detail
