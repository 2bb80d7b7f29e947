// A wave of paths as planes (one array per field of the path state), the form in which both
// schedulers hand paths to the integrator's shading step: eight neighbouring paths' fields load
// with one instruction each, and the live paths are packed to the front after every bounce
// without a queue of indices.
#pragma once

#include <immintrin.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/ray_planes.h"
#include "math/ray.h"
#include "math/vec.h"
#include "render/path_reuse.h"
#include "render/simd8.h"

namespace tuneray {

// What a path is after its steps so far. A path ray always spans [0, inf).
struct PathWave {
  enum Plane {
    kOrgX,
    kOrgY,
    kOrgZ,
    kDirX,
    kDirY,
    kDirZ,  // the ray to trace next
    kLX,
    kLY,
    kLZ,  // radiance gathered (the part a clamp may cut)
    // Emission the camera sees directly or through specular (delta) vertices only, e.g. a
    // lamp reflected in water: part of the visible scene, not a firefly, so never clamped.
    kCameraX,
    kCameraY,
    kCameraZ,
    kBetaX,
    kBetaY,
    kBetaZ,  // throughput
    kPrevX,
    kPrevY,
    kPrevZ,         // the previous vertex (for the MIS of emitters it hits)
    kPrevPdf,       // the solid-angle pdf of the direction sampled there
    kMaxRoughness,  // path-space regularization: the roughest vertex so far
    // A path that trains the radiance cache (render/radiance_cache.h): its radiance as it
    // arrived at the vertex after the cached one, its throughput into the cached vertex times
    // the albedo there (NaN in a channel the path did not carry), and its cell's key (as the
    // bits of two floats; 0: the path trains nothing). Only compacted with_cache.
    kTrainLX,
    kTrainLY,
    kTrainLZ,
    kTrainBetaX,
    kTrainBetaY,
    kTrainBetaZ,
    kCacheKeyLo,
    kCacheKeyHi,
    kFloatPlanes
  };
  static constexpr int kCorePlanes = kTrainLX;
  // Bits of `flags`.
  static constexpr int32_t kPreviousWasDelta = 1;  // the last direction came from a Dirac lobe
  static constexpr int32_t kSpecularChain = 2;     // every vertex so far was specular

  size_t size = 0;          // live paths, at positions [0, size)
  bool with_cache = false;  // the radiance cache's planes are in use
  std::array<std::vector<float>, kFloatPlanes> f;
  std::vector<int32_t> depth;  // index of the vertex the ray will hit (0 = camera ray)
  std::vector<int32_t> flags;
  std::vector<uint32_t> slot;  // the path's sample slot (its sampler and its result)
  // Per slot, when path reuse is on (path_reuse.h): the shading step records the first two
  // vertices there. Null: off.
  ReuseVertices* reuse = nullptr;

  float* plane(int p) { return f[static_cast<size_t>(p)].data(); }
  const float* plane(int p) const { return f[static_cast<size_t>(p)].data(); }

  // Room for n paths (rounded up to whole groups of eight, which the shading step reads).
  void reserve(size_t n) {
    const size_t padded = (n + 7) / 8 * 8;
    for (auto& v : f) v.resize(padded);
    depth.resize(padded);
    flags.resize(padded);
    slot.resize(padded);
  }

  // Path i starts on the camera ray `ray` (as the slot's sample `s`).
  void start(size_t i, const Ray& ray, uint32_t s) {
    float* p[kFloatPlanes];
    for (int k = 0; k < kFloatPlanes; ++k) p[k] = plane(k);
    p[kOrgX][i] = ray.org.x, p[kOrgY][i] = ray.org.y, p[kOrgZ][i] = ray.org.z;
    p[kDirX][i] = ray.dir.x, p[kDirY][i] = ray.dir.y, p[kDirZ][i] = ray.dir.z;
    for (int k = kLX; k <= kCameraZ; ++k) p[k][i] = 0.0f;
    p[kBetaX][i] = p[kBetaY][i] = p[kBetaZ][i] = 1.0f;
    p[kPrevX][i] = ray.org.x, p[kPrevY][i] = ray.org.y, p[kPrevZ][i] = ray.org.z;
    p[kPrevPdf][i] = 0.0f;
    p[kMaxRoughness][i] = 0.0f;
    p[kCacheKeyLo][i] = p[kCacheKeyHi][i] = 0.0f;
    depth[i] = 0;
    flags[i] = kPreviousWasDelta | kSpecularChain;
    slot[i] = s;
  }

  // Paths [begin, begin + 8) start on camera rays (org, dir), as slots begin, begin + 1, ...
  void start8(size_t begin, const simd::V8& org, const simd::V8& dir) {
    const simd::V8 parts[] = {org, dir};
    for (int k = 0; k < 2; ++k) {
      parts[k].x.store(plane(kOrgX + 3 * k) + begin);
      parts[k].y.store(plane(kOrgY + 3 * k) + begin);
      parts[k].z.store(plane(kOrgZ + 3 * k) + begin);
    }
    for (int k = kLX; k <= kCameraZ; ++k) simd::F8(0.0f).store(plane(k) + begin);
    for (int k = kBetaX; k <= kBetaZ; ++k) simd::F8(1.0f).store(plane(k) + begin);
    org.x.store(plane(kPrevX) + begin);
    org.y.store(plane(kPrevY) + begin);
    org.z.store(plane(kPrevZ) + begin);
    simd::F8(0.0f).store(plane(kPrevPdf) + begin);
    simd::F8(0.0f).store(plane(kMaxRoughness) + begin);
    if (with_cache) {
      simd::F8(0.0f).store(plane(kCacheKeyLo) + begin);
      simd::F8(0.0f).store(plane(kCacheKeyHi) + begin);
    }
    simd::I8(0).store(depth.data() + begin);
    simd::I8(kPreviousWasDelta | kSpecularChain).store(flags.data() + begin);
    const simd::I8 index(_mm256_add_epi32(_mm256_set1_epi32(static_cast<int32_t>(begin)),
                                          _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
    index.store(reinterpret_cast<int32_t*>(slot.data() + begin));
  }

  Ray ray(size_t i) const { return ray_planes().ray(i); }
  Color radiance(size_t i) const { return {plane(kLX)[i], plane(kLY)[i], plane(kLZ)[i]}; }
  Color camera_radiance(size_t i) const {
    return {plane(kCameraX)[i], plane(kCameraY)[i], plane(kCameraZ)[i]};
  }
  uint64_t cache_key(size_t i) const {
    return std::bit_cast<uint32_t>(plane(kCacheKeyLo)[i]) |
           uint64_t{std::bit_cast<uint32_t>(plane(kCacheKeyHi)[i])} << 32;
  }
  void set_cache_key(size_t i, uint64_t key) {
    plane(kCacheKeyLo)[i] = std::bit_cast<float>(static_cast<uint32_t>(key));
    plane(kCacheKeyHi)[i] = std::bit_cast<float>(static_cast<uint32_t>(key >> 32));
  }
  // Path i trains the cache's cell `key`; it arrived at the cached vertex with throughput
  // `beta`, and the albedo there is `albedo`.
  void mark_for_cache(size_t i, uint64_t key, Color beta, Color albedo) {
    set_cache_key(i, key);
    const float b[3] = {beta.x, beta.y, beta.z}, a[3] = {albedo.x, albedo.y, albedo.z};
    // A channel the path no longer carries says nothing about the light there (a red wall
    // before the vertex leaves green and blue at 0): it is no sample, not a zero.
    for (int k = 0; k < 3; ++k)
      plane(kTrainBetaX + k)[i] = b[k] > 0.0f ? b[k] * a[k] : std::nanf("");
  }
  // A training path arrives at the vertex after its cached one: what it has so far.
  void snapshot_for_cache(size_t i) {
    for (int k = 0; k < 3; ++k) plane(kTrainLX + k)[i] = plane(kLX + k)[i];
  }
  // What a training path found beyond its cached vertex, over its throughput into it times the
  // albedo there: the cell's incident term (radiance_cache.h); NaN where it is no sample. A
  // channel of albedo 0 reflects nothing, so its (valid) sample is 0.
  Color cache_incident(size_t i) const {
    float c[3];
    for (int k = 0; k < 3; ++k) {
      const float weight = plane(kTrainBetaX + k)[i];
      c[k] = weight > 0.0f ? (plane(kLX + k)[i] - plane(kTrainLX + k)[i]) / weight
                           : (weight == 0.0f ? 0.0f : weight);
    }
    return {c[0], c[1], c[2]};
  }
  void add_radiance(size_t i, Color c) {
    plane(kLX)[i] += c.x;
    plane(kLY)[i] += c.y;
    plane(kLZ)[i] += c.z;
  }

  // The rays of paths [0, size), as the accelerator's batch calls take them.
  RayPlanes ray_planes() const {
    return {{plane(kOrgX), plane(kOrgY), plane(kOrgZ)},
            {plane(kDirX), plane(kDirY), plane(kDirZ)},
            size};
  }

  // Keeps the paths whose bit is set in alive[i / 8] (bit i % 8), in order, at [0, count).
  void compact(std::span<const uint8_t> alive);
};

}  // namespace tuneray
