#include "accel/bvh_packet.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "accel/bvh_traverse_impl.h"
#include "accel/kernel_isa.h"
#include "math/transpose8.h"

namespace tuneray::bvh {

// The stream kernels twice: for AVX2, with 8-ray packets, and for CPUs with AVX-512 (F, VL, BW,
// DQ), with 16-ray packets in 512-bit vectors and mask registers, as Embree traces 16-ray packets
// there. The wider packets traced camera rays in 1-20 % less time (docs/bvh.md, fortieth session).
#define TUNERAY_PACKET_LANES 8
namespace avx2 {
#include "accel/bvh_packet_kernel.inc"
}  // namespace avx2
#undef TUNERAY_PACKET_LANES

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx512f,avx512vl,avx512bw,avx512dq"))), \
                             apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx512f,avx512vl,avx512bw,avx512dq")
#endif
#define TUNERAY_PACKET_LANES 16
// GCC 12's AVX-512 intrinsics (_mm512_max_ps, _mm512_extractf64x4_pd, ...) fill their unused
// merge operand from a self-initialised _mm512_undefined_ps(), which its -Wuninitialized reports
// in the caller (GCC bug 105593, fixed in GCC 13).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
namespace avx512 {
#include "accel/bvh_packet_kernel.inc"
}  // namespace avx512
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#undef TUNERAY_PACKET_LANES
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

IntersectBatchKernel select_coherent_batch_kernel(const TreeShape& shape) {
  return kernel_isa() == KernelIsa::kAvx512 ? avx512::coherent_batch_kernel(shape)
                                            : avx2::coherent_batch_kernel(shape);
}

IntersectPlanesKernel select_coherent_planes_kernel(const TreeShape& shape) {
  return kernel_isa() == KernelIsa::kAvx512 ? avx512::coherent_planes_kernel(shape)
                                            : avx2::coherent_planes_kernel(shape);
}

}  // namespace tuneray::bvh
