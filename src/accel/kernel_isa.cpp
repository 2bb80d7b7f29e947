#include "accel/kernel_isa.h"

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>

namespace tuneray::bvh {

bool cpu_has_avx512() {
  // libgcc's checks include the operating system's support for the AVX-512 state (XCR0).
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
           __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  }();
  return has;
}

KernelIsa kernel_isa() {
  const char* env = std::getenv("TUNERAY_KERNEL_ISA");
  const std::string_view cap = env ? env : "";
  if (cap.empty() || cap == "avx512")
    return cpu_has_avx512() ? KernelIsa::kAvx512 : KernelIsa::kAvx2;
  if (cap == "avx2") return KernelIsa::kAvx2;
  throw std::invalid_argument("TUNERAY_KERNEL_ISA is '" + std::string(cap) +
                              "'; it takes avx2 or avx512");
}

const char* to_string(KernelIsa isa) {
  return isa == KernelIsa::kAvx512 ? "avx512" : "avx2";
}

}  // namespace tuneray::bvh
