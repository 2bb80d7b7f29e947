// A wave of paths as planes (one array per field of the path state), the form in which both
// schedulers hand paths to the integrator's shading step: eight neighbouring paths' fields load
// with one instruction each, and the live paths are packed to the front after every bounce
// without a queue of indices.
#pragma once

#include <immintrin.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/ray_planes.h"
#include "math/ray.h"
#include "math/vec.h"
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
    kFloatPlanes
  };
  // Bits of `flags`.
  static constexpr int32_t kPreviousWasDelta = 1;  // the last direction came from a Dirac lobe
  static constexpr int32_t kSpecularChain = 2;     // every vertex so far was specular

  size_t size = 0;  // live paths, at positions [0, size)
  std::array<std::vector<float>, kFloatPlanes> f;
  std::vector<int32_t> depth;  // index of the vertex the ray will hit (0 = camera ray)
  std::vector<int32_t> flags;
  std::vector<uint32_t> slot;  // the path's sample slot (its sampler and its result)

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
