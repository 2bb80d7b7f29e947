#include "accel/bvh_packet.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "accel/bvh_traverse_impl.h"
#include "accel/kernel_isa.h"
#include "math/transpose8.h"

namespace tuneray::bvh {

// The stream kernels twice: for AVX2, and for CPUs with AVX-512 (F, VL, BW, DQ), where Embree
// runs its AVX-512 kernels too. The AVX-512 copy is the same source, still 256 bits wide, that
// the compiler gives 32 vector registers (a stream's node step holds 16 vectors of per-packet
// state) and mask registers; it traces camera rays in up to 13 % less time (docs/bvh.md).
namespace avx2 {
#include "accel/bvh_packet_kernel.inc"
}  // namespace avx2

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx512f,avx512vl,avx512bw,avx512dq"))), \
                             apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx512f,avx512vl,avx512bw,avx512dq")
#endif
namespace avx512 {
#include "accel/bvh_packet_kernel.inc"
}  // namespace avx512
#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif

IntersectBatchKernel select_coherent_batch_kernel(const TreeShape& shape) {
  return kernel_isa() == KernelIsa::kAvx512 ? avx512::coherent_batch_kernel(shape)
                                            : avx2::coherent_batch_kernel(shape);
}

}  // namespace tuneray::bvh
