// Embree's own BVH and traversal (rtcNewScene + rtcIntersect/rtcOccluded): the reference
// backend that the tuned BVH is measured and checked against.
#pragma once

#include <embree3/rtcore.h>

#include <memory>

#include "accel/accel.h"
#include "accel/embree_device.h"

namespace tuneray {

struct NativeOptions {
  RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM;
  bool robust = false;   // RTC_SCENE_FLAG_ROBUST
  bool compact = false;  // RTC_SCENE_FLAG_COMPACT
  bool dynamic = false;  // RTC_SCENE_FLAG_DYNAMIC
};

class EmbreeNativeAccel final : public Accel {
 public:
  explicit EmbreeNativeAccel(NativeOptions options = {},
                             std::shared_ptr<EmbreeDevice> device = EmbreeDevice::shared());
  ~EmbreeNativeAccel() override;

  void set_options(const NativeOptions& options) { options_ = options; }
  const NativeOptions& options() const { return options_; }

  std::string name() const override { return "native"; }
  std::string describe() const override;
  BuildStats build(const GeometryView& geometry) override;
  bool intersect(const Ray& ray, Hit& hit) const override;
  bool occluded(const Ray& ray) const override;
  void intersect_batch(std::span<const Ray> rays, std::span<Hit> hits,
                       RayCoherence coherence = RayCoherence::kIncoherent) const override;
  void occluded_batch(std::span<const Ray> rays, std::span<uint8_t> occluded) const override;

 private:
  void release();
  NativeOptions options_;
  std::shared_ptr<EmbreeDevice> device_;
  RTCScene scene_ = nullptr;
};

}  // namespace tuneray
