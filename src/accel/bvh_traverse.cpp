#include "accel/bvh_traverse.h"

#include "accel/bvh_traverse_impl.h"
#include "accel/kernel_isa.h"

namespace tuneray::bvh {

// The single-ray kernels twice: for AVX2 (tuneray::bvh::single) and for CPUs with AVX-512, where
// the same source compiled for AVX-512 VL keeps the ray's terms in 32 vector registers instead of
// reloading them at every node: bounce rays 2-5 % less time on a Zen 4 host (docs/bvh.md,
// forty-sixth session), as Embree runs its AVX-512 build of its BVH8 kernels there.
namespace avx2 {
#include "accel/bvh_traverse_entry.inc"
}  // namespace avx2

#include "accel/avx512_target_begin.inc"
namespace avx512 {
namespace single {
#include "accel/bvh_traverse_kernel.inc"
}  // namespace single
#include "accel/bvh_traverse_entry.inc"
}  // namespace avx512
#include "accel/avx512_target_end.inc"

Kernels select_kernels(const TreeShape& shape) {
  return kernel_isa() == KernelIsa::kAvx512 ? avx512::select_kernels_here(shape)
                                            : avx2::select_kernels_here(shape);
}

}  // namespace tuneray::bvh
