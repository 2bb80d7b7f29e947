// The choice between the kernels' instruction-set copies (kernel_isa.h).
#include "accel/kernel_isa.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "kernel_isa_cap.h"

namespace tuneray::test {
namespace {

using bvh::KernelIsa;

// Runs `check` with TUNERAY_KERNEL_ISA set to `value` (unset for nullptr), then restores it.
template <class Check>
void with_cap(const char* value, Check check) {
  const KernelIsaCap cap(value);
  check();
}

TEST(KernelIsa, UncappedItIsTheWidestTheCpuRuns) {
  const KernelIsa widest = bvh::cpu_has_avx512() ? KernelIsa::kAvx512 : KernelIsa::kAvx2;
  with_cap(nullptr, [&] { EXPECT_EQ(bvh::kernel_isa(), widest); });
  with_cap("", [&] { EXPECT_EQ(bvh::kernel_isa(), widest); });
  with_cap("avx512", [&] { EXPECT_EQ(bvh::kernel_isa(), widest); });
}

TEST(KernelIsa, Avx2CapsIt) {
  with_cap("avx2", [] { EXPECT_EQ(bvh::kernel_isa(), KernelIsa::kAvx2); });
}

TEST(KernelIsa, AnUnknownCapIsRefusedByName) {
  with_cap("avx1024", [] {
    try {
      bvh::kernel_isa();
      FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("TUNERAY_KERNEL_ISA"), std::string::npos) << what;
      EXPECT_NE(what.find("avx1024"), std::string::npos) << what;
    }
  });
}

TEST(KernelIsa, NamesAreTheCapsValues) {
  EXPECT_STREQ(bvh::to_string(KernelIsa::kAvx2), "avx2");
  EXPECT_STREQ(bvh::to_string(KernelIsa::kAvx512), "avx512");
}

}  // namespace
}  // namespace tuneray::test
