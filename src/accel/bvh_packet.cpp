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

#include "accel/avx512_target_begin.inc"
#define TUNERAY_PACKET_LANES 16
namespace avx512 {
// The streams' hand-over and ray-by-ray leaf tests run the AVX-512 copy of the single-ray
// kernels (found as `single` from inside this namespace before tuneray::bvh::single).
namespace single {
#include "accel/bvh_traverse_kernel.inc"
}  // namespace single
#include "accel/bvh_packet_kernel.inc"
}  // namespace avx512
#undef TUNERAY_PACKET_LANES
#include "accel/avx512_target_end.inc"

IntersectBatchKernel select_coherent_batch_kernel(const TreeShape& shape) {
  return kernel_isa() == KernelIsa::kAvx512 ? avx512::coherent_batch_kernel(shape)
                                            : avx2::coherent_batch_kernel(shape);
}

IntersectPlanesKernel select_coherent_planes_kernel(const TreeShape& shape) {
  return kernel_isa() == KernelIsa::kAvx512 ? avx512::coherent_planes_kernel(shape)
                                            : avx2::coherent_planes_kernel(shape);
}

}  // namespace tuneray::bvh
