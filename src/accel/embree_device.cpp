#include "accel/embree_device.h"

#include <map>
#include <mutex>
#include <stdexcept>

namespace tuneray {

namespace {
const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "none";
    case RTC_ERROR_UNKNOWN:
      return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
  }
  return "unknown error";
}
std::mutex g_error_mutex;
}  // namespace

EmbreeDevice::EmbreeDevice(const std::string& config) {
  device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!device_) {
    throw std::runtime_error("Embree: cannot create device (" +
                             std::string(error_name(rtcGetDeviceError(nullptr))) + ")");
  }
  rtcSetDeviceErrorFunction(device_, &EmbreeDevice::on_error, this);
}

EmbreeDevice::~EmbreeDevice() {
  rtcReleaseDevice(device_);
}

void EmbreeDevice::on_error(void* user, RTCError code, const char* message) {
  auto* self = static_cast<EmbreeDevice*>(user);
  std::lock_guard lock(g_error_mutex);
  self->last_error_ = std::string(error_name(code)) + (message ? std::string(": ") + message : "");
}

std::string EmbreeDevice::take_error() {
  std::lock_guard lock(g_error_mutex);
  std::string e;
  e.swap(last_error_);
  return e;
}

std::shared_ptr<EmbreeDevice> EmbreeDevice::shared() {
  static std::shared_ptr<EmbreeDevice> device = std::make_shared<EmbreeDevice>();
  return device;
}

std::shared_ptr<EmbreeDevice> EmbreeDevice::shared(const std::string& config) {
  if (config.empty()) return shared();
  static std::mutex mutex;
  static std::map<std::string, std::weak_ptr<EmbreeDevice>> devices;
  std::lock_guard lock(mutex);
  std::weak_ptr<EmbreeDevice>& slot = devices[config];
  if (auto device = slot.lock()) return device;
  auto device = std::make_shared<EmbreeDevice>(config);
  slot = device;
  return device;
}

}  // namespace tuneray
