// Embree's own BVH and traversal (rtcNewScene + rtcIntersect/rtcOccluded): the reference
// backend that the tuned BVH is measured and checked against.
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/embree_device.h"

namespace tuneray {

struct NativeOptions {
  RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM;
  bool robust = false;   // RTC_SCENE_FLAG_ROBUST
  bool compact = false;  // RTC_SCENE_FLAG_COMPACT
  bool dynamic = false;  // RTC_SCENE_FLAG_DYNAMIC
  // Embree's device-level choices for triangle meshes (its `tri_accel` and `tri_builder`), empty
  // for Embree's default: the BVH's width and leaf kind (e.g. bvh4.triangle4v) and its builder
  // (e.g. sah_presplit). A backend that sets either builds on a device of its own.
  std::string tri_accel;
  std::string tri_builder;

  // The rtcNewDevice string of the two choices above ("" when both are Embree's default).
  std::string device_config() const;
  // Why these options cannot be built as asked, or "" when they can. Embree builds a named
  // tri_accel at its static medium settings and ignores the scene's quality and flags, so a
  // named BVH or builder goes only with quality=medium and no robust, compact or dynamic flag
  // (robust=1 would otherwise silently not be robust).
  std::string problem() const;
};

// The values NativeOptions::tri_accel and tri_builder accept (Embree 3.13's static triangle
// BVHs and their builders); anything else is refused before Embree sees it.
const std::vector<std::string>& native_tri_accels();
const std::vector<std::string>& native_tri_builders();

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
  void intersect_planes(const RayPlanes& rays, std::span<Hit> hits,
                        RayCoherence coherence = RayCoherence::kIncoherent) const override;

 private:
  void release();
  // Closest hits of n rays as rtcIntersect8 packets; load(i, count, active, packet) writes the
  // origins, directions, tnear and tfar of rays [i, i + count) into the packet's lanes
  // [0, count), whose lanes of `active` are all ones.
  template <class LoadPacket>
  void intersect_packets(size_t n, LoadPacket load, std::span<Hit> hits) const;
  void intersect_stream(const RayPlanes& rays, std::span<Hit> hits) const;
  NativeOptions options_;
  std::shared_ptr<EmbreeDevice> device_;
  // The device the scene was built on: device_, or one of options_.device_config().
  std::shared_ptr<EmbreeDevice> scene_device_;
  RTCScene scene_ = nullptr;
};

}  // namespace tuneray
