// One Embree device per process, with errors turned into messages we can report.
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <string>

namespace tuneray {

class EmbreeDevice {
 public:
  // `config` is Embree's device string, e.g. "threads=2". Note that "threads=N" limits TBB for
  // the whole process, our own parallel loops included.
  explicit EmbreeDevice(const std::string& config = "");
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }

  // The last error Embree reported since the previous call (empty if none); clears it.
  std::string take_error();

  static std::shared_ptr<EmbreeDevice> shared();
  // The device of this configuration string, one per distinct string while any user holds it
  // ("" is shared()). Embree reads some choices only per device (the triangle BVH's kind and
  // builder: tri_accel, tri_builder), so a backend asking for them needs its own device.
  static std::shared_ptr<EmbreeDevice> shared(const std::string& config);

 private:
  static void on_error(void* user, RTCError code, const char* message);
  RTCDevice device_ = nullptr;
  std::string last_error_;
};

}  // namespace tuneray
