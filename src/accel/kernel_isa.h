// Which instruction set the tuned BVH's dispatched kernels run with. Embree picks its kernels by
// the CPU (AVX-512 where there is one); so do we, for the kernels compiled in more than one copy
// (bvh_packet.cpp). The environment variable TUNERAY_KERNEL_ISA caps the choice (`avx2` or
// `avx512`): to measure both copies in one binary (`batch_replay --ab-env`) and to test both.
#pragma once

namespace tuneray::bvh {

enum class KernelIsa { kAvx2, kAvx512 };

// The widest set this CPU runs and TUNERAY_KERNEL_ISA allows. Throws std::invalid_argument when
// the variable holds anything but avx2 or avx512.
KernelIsa kernel_isa();

// True when the CPU (and its operating system) runs the AVX-512 copies: F, VL, BW and DQ.
bool cpu_has_avx512();

const char* to_string(KernelIsa isa);

}  // namespace tuneray::bvh
