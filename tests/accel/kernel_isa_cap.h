// Sets TUNERAY_KERNEL_ISA (or unsets it, for nullptr) for the lifetime of the object and then
// restores what was there: trees built meanwhile select that copy of the kernels.
#pragma once

#include <cstdlib>
#include <optional>
#include <string>

namespace tuneray::test {

class KernelIsaCap {
 public:
  explicit KernelIsaCap(const char* value) {
    if (const char* before = std::getenv(kVariable)) saved_ = before;
    set(value);
  }
  ~KernelIsaCap() { set(saved_ ? saved_->c_str() : nullptr); }
  KernelIsaCap(const KernelIsaCap&) = delete;
  KernelIsaCap& operator=(const KernelIsaCap&) = delete;

 private:
  static constexpr const char* kVariable = "TUNERAY_KERNEL_ISA";
  static void set(const char* value) {
    if (value) {
      setenv(kVariable, value, 1);
    } else {
      unsetenv(kVariable);
    }
  }
  std::optional<std::string> saved_;
};

}  // namespace tuneray::test
