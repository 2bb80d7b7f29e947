#include "accel/embree_native.h"

#include <immintrin.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

#include "scene/scene.h"

namespace tuneray {

namespace {
const char* quality_name(RTCBuildQuality q) {
  switch (q) {
    case RTC_BUILD_QUALITY_LOW:
      return "low";
    case RTC_BUILD_QUALITY_HIGH:
      return "high";
    default:
      return "medium";
  }
}

// A ray in Embree's layout, with whole-register moves: Ray's first 28 bytes are RTCRay's
// (origin, tnear, direction); its tfar sits where RTCRay's time does. The batch calls copy every
// ray, twice per bounce, so the copy is a measurable part of a frame.
inline void store_rtc(const Ray& r, RTCRay& out) {
  static_assert(sizeof(Ray) == 32 && offsetof(Ray, tfar) == 28);
  static_assert(offsetof(RTCRay, time) == 28 && offsetof(RTCRay, flags) == 44);
  const __m256 row = _mm256_loadu_ps(reinterpret_cast<const float*>(&r));
  _mm256_storeu_ps(&out.org_x, _mm256_blend_ps(row, _mm256_setzero_ps(), 0x80));
  // tfar, then mask (all bits), id and flags (0).
  const __m128i tail =
      _mm_setr_epi32(_mm_cvtsi128_si32(_mm_castps_si128(_mm_set_ss(r.tfar))), -1, 0, 0);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(&out.tfar), tail);
}

inline void store_rtc_hit(const Ray& r, RTCRayHit& out) {
  store_rtc(r, out.ray);
  out.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  out.hit.primID = RTC_INVALID_GEOMETRY_ID;
  out.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

inline bool from_rtc_hit(const RTCRayHit& rh, Hit& hit) {
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit.t = rh.ray.tfar;
  hit.prim = rh.hit.primID;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  return true;
}
}  // namespace

// Embree 3.13 also names quantized BVHs (qbvh4.triangle4i, qbvh8.triangle4, qbvh8.triangle4i),
// but they have no stream intersector: rtcIntersect1M on them fails an assertion inside Embree.
const std::vector<std::string>& native_tri_accels() {
  static const std::vector<std::string> names = {"bvh4.triangle4",  "bvh4.triangle4v",
                                                 "bvh4.triangle4i", "bvh8.triangle4",
                                                 "bvh8.triangle4v", "bvh8.triangle4i"};
  return names;
}

const std::vector<std::string>& native_tri_builders() {
  static const std::vector<std::string> names = {"sah", "sah_fast_spatial", "sah_presplit"};
  return names;
}

std::string NativeOptions::device_config() const {
  std::string config;
  if (!tri_accel.empty()) config.append("tri_accel=").append(tri_accel);
  if (!tri_builder.empty()) {
    if (!config.empty()) config.push_back(',');
    config.append("tri_builder=").append(tri_builder);
  }
  return config;
}

std::string NativeOptions::problem() const {
  if (tri_accel.empty() && tri_builder.empty()) return "";
  const auto unknown = [](const char* key, const std::vector<std::string>& names,
                          const std::string& name) -> std::string {
    if (name.empty() || std::find(names.begin(), names.end(), name) != names.end()) return "";
    std::string valid;
    for (const auto& n : names) valid += (valid.empty() ? "" : "|") + n;
    return std::string("parameter '") + key + "': expected " + valid + ", got '" + name + "'";
  };
  if (std::string e = unknown("tri_accel", native_tri_accels(), tri_accel); !e.empty()) return e;
  if (std::string e = unknown("tri_builder", native_tri_builders(), tri_builder); !e.empty())
    return e;
  if (quality != RTC_BUILD_QUALITY_MEDIUM || robust || compact || dynamic)
    return "tri_accel and tri_builder go only with quality=medium, robust=0, compact=0 and "
           "dynamic=0 (Embree builds a named BVH at its static medium settings)";
  return "";
}

EmbreeNativeAccel::EmbreeNativeAccel(NativeOptions options, std::shared_ptr<EmbreeDevice> device)
    : options_(options), device_(std::move(device)) {}

EmbreeNativeAccel::~EmbreeNativeAccel() {
  release();
}

void EmbreeNativeAccel::release() {
  if (scene_) rtcReleaseScene(scene_);
  scene_ = nullptr;
  scene_device_.reset();
}

std::string EmbreeNativeAccel::describe() const {
  std::string text = std::string("quality=") + quality_name(options_.quality) +
                     ",robust=" + (options_.robust ? "1" : "0") +
                     ",compact=" + (options_.compact ? "1" : "0") +
                     ",dynamic=" + (options_.dynamic ? "1" : "0");
  if (!options_.tri_accel.empty()) text += ",tri_accel=" + options_.tri_accel;
  if (!options_.tri_builder.empty()) text += ",tri_builder=" + options_.tri_builder;
  return text;
}

BuildStats EmbreeNativeAccel::build(const GeometryView& geometry) {
  release();
  if (const std::string problem = options_.problem(); !problem.empty())
    throw BuildError("Embree native: " + problem);
  auto start = std::chrono::steady_clock::now();
  const std::string config = options_.device_config();
  scene_device_ = config.empty() ? device_ : EmbreeDevice::shared(config);
  EmbreeDevice& device = *scene_device_;
  device.take_error();

  RTCDevice dev = device.get();
  scene_ = rtcNewScene(dev);
  int flags = RTC_SCENE_FLAG_NONE;
  if (options_.robust) flags |= RTC_SCENE_FLAG_ROBUST;
  if (options_.compact) flags |= RTC_SCENE_FLAG_COMPACT;
  if (options_.dynamic) flags |= RTC_SCENE_FLAG_DYNAMIC;
  rtcSetSceneFlags(scene_, static_cast<RTCSceneFlags>(flags));
  rtcSetSceneBuildQuality(scene_, options_.quality);

  if (geometry.triangle_count > 0) {
    RTCGeometry geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Embree-owned copies: Embree may read 16 bytes at the last vertex, so its buffers are
    // padded; sharing our tightly packed arrays would read past their end.
    auto* vertices = static_cast<Vec3f*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(Vec3f), geometry.vertex_count));
    auto* indices = static_cast<Triangle*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(Triangle),
                                geometry.triangle_count));
    if (!vertices || !indices) {
      rtcReleaseGeometry(geom);
      release();
      throw BuildError("Embree native build failed: " + device.take_error());
    }
    std::copy_n(geometry.positions, geometry.vertex_count, vertices);
    std::copy_n(geometry.triangles, geometry.triangle_count, indices);
    rtcSetGeometryBuildQuality(geom, options_.quality);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene_, geom, 0);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(scene_);

  std::string error = device.take_error();
  if (!error.empty()) {
    release();
    throw BuildError("Embree native build failed: " + error);
  }
  BuildStats stats;
  stats.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

bool EmbreeNativeAccel::intersect(const Ray& ray, Hit& hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  store_rtc_hit(ray, rh);
  rtcIntersect1(scene_, &context, &rh);
  return from_rtc_hit(rh, hit);
}

bool EmbreeNativeAccel::occluded(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r;
  store_rtc(ray, r);
  rtcOccluded1(scene_, &context, &r);
  return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

void EmbreeNativeAccel::intersect_batch(std::span<const Ray> rays, std::span<Hit> hits,
                                        RayCoherence coherence) const {
  thread_local std::vector<RTCRayHit> buffer;
  buffer.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) store_rtc_hit(rays[i], buffer[i]);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  // Coherent streams go through Embree's packet traversal: a frame of camera rays alone renders
  // 1.25x faster; on scattered rays the flag makes a frame 1.5x slower (Cornell box, 320x240).
  context.flags = coherence == RayCoherence::kCoherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                                       : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  rtcIntersect1M(scene_, &context, buffer.data(), static_cast<unsigned>(rays.size()),
                 sizeof(RTCRayHit));
  for (size_t i = 0; i < rays.size(); ++i) {
    hits[i] = Hit{};
    from_rtc_hit(buffer[i], hits[i]);
  }
}

void EmbreeNativeAccel::occluded_batch(std::span<const Ray> rays,
                                       std::span<uint8_t> occluded_out) const {
  thread_local std::vector<RTCRay> buffer;
  buffer.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) store_rtc(rays[i], buffer[i]);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  rtcOccluded1M(scene_, &context, buffer.data(), static_cast<unsigned>(rays.size()),
                sizeof(RTCRay));
  for (size_t i = 0; i < rays.size(); ++i) occluded_out[i] = buffer[i].tfar < 0.0f ? 1 : 0;
}

}  // namespace tuneray
