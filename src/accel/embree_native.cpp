#include "accel/embree_native.h"

#include <immintrin.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "math/transpose8.h"
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
  __m256 row = _mm256_loadu_ps(reinterpret_cast<const float*>(&r));
  // Embree asks tnear >= 0; a negative or NaN one reads as 0, as in the tuned BVH (max_ps
  // returns its second operand for a NaN).
  row = _mm256_blend_ps(row, _mm256_max_ps(row, _mm256_setzero_ps()), 0x08);
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

// Eight hit records (t, prim, u, v) from Embree's hit planes, a miss as Hit{}: a 4x8 transpose.
// The planes hold eight readable lanes; hits [0, count) are written.
void store_hits8(const float* tfar, const unsigned* prim_id, const float* u_plane,
                 const float* v_plane, const unsigned* geom_id, size_t count, Hit* hits) {
  const __m256i invalid = _mm256_set1_epi32(static_cast<int>(RTC_INVALID_GEOMETRY_ID));
  const __m256 miss = _mm256_castsi256_ps(
      _mm256_cmpeq_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(geom_id)), invalid));
  const __m256 t = _mm256_blendv_ps(_mm256_loadu_ps(tfar), _mm256_set1_ps(kInf), miss);
  const __m256 prim = _mm256_or_ps(_mm256_loadu_ps(reinterpret_cast<const float*>(prim_id)), miss);
  const __m256 u = _mm256_andnot_ps(miss, _mm256_loadu_ps(u_plane));
  const __m256 v = _mm256_andnot_ps(miss, _mm256_loadu_ps(v_plane));
  const __m256 tp_lo = _mm256_unpacklo_ps(t, prim), tp_hi = _mm256_unpackhi_ps(t, prim);
  const __m256 uv_lo = _mm256_unpacklo_ps(u, v), uv_hi = _mm256_unpackhi_ps(u, v);
  const __m256 h04 = _mm256_shuffle_ps(tp_lo, uv_lo, 0x44),
               h15 = _mm256_shuffle_ps(tp_lo, uv_lo, 0xEE);
  const __m256 h26 = _mm256_shuffle_ps(tp_hi, uv_hi, 0x44),
               h37 = _mm256_shuffle_ps(tp_hi, uv_hi, 0xEE);
  static_assert(sizeof(Hit) == 4 * sizeof(float) && offsetof(Hit, prim) == 4 &&
                offsetof(Hit, u) == 8 && offsetof(Hit, v) == 12);
  alignas(32) Hit staged[8];
  float* o = reinterpret_cast<float*>(count == 8 ? hits : staged);
  _mm256_storeu_ps(o, _mm256_permute2f128_ps(h04, h15, 0x20));
  _mm256_storeu_ps(o + 8, _mm256_permute2f128_ps(h26, h37, 0x20));
  _mm256_storeu_ps(o + 16, _mm256_permute2f128_ps(h04, h15, 0x31));
  _mm256_storeu_ps(o + 24, _mm256_permute2f128_ps(h26, h37, 0x31));
  if (count < 8) std::copy_n(staged, count, hits);
}

// The planes of a coherent stream that the wavefront does not keep: the constant inputs, and
// the outputs Embree writes. Per thread, kept between calls; every plane has whole groups of 8.
struct StreamPlanes {
  std::vector<float> zero, tfar, ng_x, ng_y, ng_z, u, v;
  std::vector<unsigned> all_bits, zero_bits, prim, geom, inst;
  void prepare(size_t n) {
    const size_t padded = (n + 7) / 8 * 8;
    if (zero.size() < padded) {
      zero.assign(padded, 0.0f);
      all_bits.assign(padded, ~0u);
      zero_bits.assign(padded, 0u);
      for (auto* plane : {&tfar, &ng_x, &ng_y, &ng_z, &u, &v}) plane->resize(padded);
      for (auto* plane : {&prim, &geom, &inst}) plane->resize(padded);
    }
    std::fill_n(tfar.begin(), n, kInf);
    std::fill_n(geom.begin(), padded, RTC_INVALID_GEOMETRY_ID);  // also the unused lanes
  }
};

bool aligned16(const float* p) {
  return (reinterpret_cast<uintptr_t>(p) & 15) == 0;
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

// Incoherent closest-hit batches go to Embree as 8-ray packets in its SoA layout. rtcIntersect1M
// traces such a batch with the same packet kernel, but gathers every packet from the records
// and scatters the hits back first (batch_replay, bounce rays, rtcIntersect8 over
// rtcIntersect1M: Embree's Cornell box 1.08-1.11x, conference 1.03-1.04x). Shadow rays keep
// rtcOccluded1M, which sorts them by octant into streams: as packets they were 0.72-0.82x on
// conference and lost-empire.
template <class LoadPacket>
void EmbreeNativeAccel::intersect_packets(size_t n, LoadPacket load, std::span<Hit> hits) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  alignas(32) RTCRayHit8 packet;
  alignas(32) int valid[8];
  _mm256_store_ps(packet.ray.time, _mm256_setzero_ps());
  _mm256_store_si256(reinterpret_cast<__m256i*>(packet.ray.mask), _mm256_set1_epi32(-1));
  _mm256_store_si256(reinterpret_cast<__m256i*>(packet.ray.id), _mm256_setzero_si256());
  _mm256_store_si256(reinterpret_cast<__m256i*>(packet.ray.flags), _mm256_setzero_si256());
  const __m256i invalid = _mm256_set1_epi32(static_cast<int>(RTC_INVALID_GEOMETRY_ID));
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (size_t i = 0; i < n; i += 8) {
    const size_t count = std::min<size_t>(8, n - i);
    const __m256i active = _mm256_cmpgt_epi32(_mm256_set1_epi32(static_cast<int>(count)), lane);
    load(i, count, active, packet);
    _mm256_store_si256(reinterpret_cast<__m256i*>(packet.hit.geomID), invalid);
    _mm256_store_si256(reinterpret_cast<__m256i*>(packet.hit.instID[0]), invalid);
    _mm256_store_si256(reinterpret_cast<__m256i*>(valid), active);
    rtcIntersect8(valid, scene_, &context, &packet);
    store_hits8(packet.ray.tfar, packet.hit.primID, packet.hit.u, packet.hit.v, packet.hit.geomID,
                count, hits.data() + i);
  }
}

// Coherent batches through Embree's stream traversal, as rtcIntersect1M's coherent mode does,
// but from the planes as they are (rtcIntersectNp): no copy into records, no gather of every
// packet from records inside Embree, no scatter of the hits back.
void EmbreeNativeAccel::intersect_stream(const RayPlanes& rays, std::span<Hit> hits) const {
  for (const float* p :
       {rays.org[0], rays.org[1], rays.org[2], rays.dir[0], rays.dir[1], rays.dir[2]})
    if (!aligned16(p)) {  // rtcIntersectNp's requirement
      Accel::intersect_planes(rays, hits, RayCoherence::kCoherent);
      return;
    }
  thread_local StreamPlanes planes;
  planes.prepare(rays.size);
  RTCRayHitNp stream;
  // Embree only reads the rays' planes (the stream filter copies each packet before tracing).
  stream.ray.org_x = const_cast<float*>(rays.org[0]);
  stream.ray.org_y = const_cast<float*>(rays.org[1]);
  stream.ray.org_z = const_cast<float*>(rays.org[2]);
  stream.ray.dir_x = const_cast<float*>(rays.dir[0]);
  stream.ray.dir_y = const_cast<float*>(rays.dir[1]);
  stream.ray.dir_z = const_cast<float*>(rays.dir[2]);
  stream.ray.tnear = planes.zero.data();
  stream.ray.time = planes.zero.data();
  stream.ray.tfar = planes.tfar.data();
  stream.ray.mask = planes.all_bits.data();
  stream.ray.id = planes.zero_bits.data();
  stream.ray.flags = planes.zero_bits.data();
  stream.hit.Ng_x = planes.ng_x.data();
  stream.hit.Ng_y = planes.ng_y.data();
  stream.hit.Ng_z = planes.ng_z.data();
  stream.hit.u = planes.u.data();
  stream.hit.v = planes.v.data();
  stream.hit.primID = planes.prim.data();
  stream.hit.geomID = planes.geom.data();
  for (auto*& inst : stream.hit.instID) inst = planes.inst.data();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersectNp(scene_, &context, &stream, static_cast<unsigned>(rays.size));
  for (size_t i = 0; i < rays.size; i += 8)
    store_hits8(planes.tfar.data() + i, planes.prim.data() + i, planes.u.data() + i,
                planes.v.data() + i, planes.geom.data() + i, std::min<size_t>(8, rays.size - i),
                hits.data() + i);
}

void EmbreeNativeAccel::intersect_planes(const RayPlanes& rays, std::span<Hit> hits,
                                         RayCoherence coherence) const {
  if (coherence == RayCoherence::kCoherent) {
    intersect_stream(rays, hits);
    return;
  }
  const auto load = [&rays](size_t i, size_t count, __m256i active, RTCRayHit8& packet) {
    // The last group reads only its rays: the planes may end there.
    float* const dst[6] = {packet.ray.org_x, packet.ray.org_y, packet.ray.org_z,
                           packet.ray.dir_x, packet.ray.dir_y, packet.ray.dir_z};
    const float* const src[6] = {rays.org[0], rays.org[1], rays.org[2],
                                 rays.dir[0], rays.dir[1], rays.dir[2]};
    for (int k = 0; k < 6; ++k)
      _mm256_store_ps(dst[k], count == 8 ? _mm256_loadu_ps(src[k] + i)
                                         : _mm256_maskload_ps(src[k] + i, active));
    _mm256_store_ps(packet.ray.tnear, _mm256_setzero_ps());
    _mm256_store_ps(packet.ray.tfar, _mm256_set1_ps(kInf));
  };
  intersect_packets(rays.size, load, hits);
}

void EmbreeNativeAccel::intersect_batch(std::span<const Ray> rays, std::span<Hit> hits,
                                        RayCoherence coherence) const {
  if (coherence == RayCoherence::kIncoherent) {
    const auto load = [rays](size_t i, size_t count, __m256i, RTCRayHit8& packet) {
      static_assert(sizeof(Ray) == 8 * sizeof(float) && offsetof(Ray, tfar) == 28);
      __m256 r[8];
      const float* src = reinterpret_cast<const float*>(rays.data() + i);
      for (size_t k = 0; k < 8; ++k)
        r[k] = k < count ? _mm256_loadu_ps(src + 8 * k) : _mm256_setzero_ps();
      transpose8(r);  // planes: org x, y, z, tnear, dir x, y, z, tfar
      r[3] = _mm256_max_ps(r[3], _mm256_setzero_ps());  // tnear >= 0, as in store_rtc
      float* const dst[8] = {packet.ray.org_x, packet.ray.org_y, packet.ray.org_z, packet.ray.tnear,
                             packet.ray.dir_x, packet.ray.dir_y, packet.ray.dir_z, packet.ray.tfar};
      for (int k = 0; k < 8; ++k) _mm256_store_ps(dst[k], r[k]);
    };
    intersect_packets(rays.size(), load, hits);
    return;
  }
  thread_local std::vector<RTCRayHit> buffer;
  buffer.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) store_rtc_hit(rays[i], buffer[i]);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  // Coherent streams go through Embree's packet traversal: a frame of camera rays alone renders
  // 1.25x faster; on scattered rays the flag makes a frame 1.5x slower (Cornell box, 320x240).
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
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
