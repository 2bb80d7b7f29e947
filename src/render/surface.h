// What the integrator knows about a hit: position, normals, shading frame, UV, material.
#pragma once

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "math/frame.h"
#include "math/ray.h"
#include "render/bsdf.h"
#include "scene/scene.h"

namespace tuneray {

struct SurfaceInteraction {
  Vec3f position;
  Vec3f geometric_normal;  // unit, from the triangle's winding
  Frame shading;           // shading.n is the interpolated normal
  Vec2f uv;
  uint32_t prim = kInvalidId;
  const Material* material = nullptr;
};

// Everything computed at the hit (the reference for ShadingGeometry, which the integrator uses).
SurfaceInteraction make_interaction(const Scene& scene, const Hit& hit);

// What an interaction reads lies in several arrays at random places for incoherent hits, so a
// batch of hits waits on memory hit after hit. A scheduler that knows the hits ahead prefetches
// in two steps: first the triangle's vertex indices (and its ShadingGeometry record), then (once
// the indices have arrived) the vertices' positions, normals and UVs.
inline void prefetch_hit_triangle(const Scene& scene, uint32_t prim) {
  _mm_prefetch(reinterpret_cast<const char*>(&scene.triangles[prim]), _MM_HINT_T0);
}
inline void prefetch_hit_vertices(const Scene& scene, uint32_t prim) {
  const Triangle& t = scene.triangles[prim];
  for (uint32_t v : t.v) {
    _mm_prefetch(reinterpret_cast<const char*>(&scene.positions[v]), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(&scene.normals[v]), _MM_HINT_T0);
    if (!scene.uvs.empty()) _mm_prefetch(reinterpret_cast<const char*>(&scene.uvs[v]), _MM_HINT_T0);
  }
}

// Resolves textures: the BSDF parameters at this point.
BsdfParams resolve_bsdf(const Scene& scene, const SurfaceInteraction& si);
// Its two parts: the material's parameters without its texture (the same at every point), and
// the factor its base texture (m.base_texture != kNoTexture) puts on base_color at `uv`.
BsdfParams untextured_bsdf(const Material& m);
Color texture_factor(const Scene& scene, const Material& m, Vec2f uv);

// Origin for a ray leaving `p` towards side `dir` of the surface with geometric normal n:
// offset along n by an amount that scales with the coordinates' magnitude (float precision).
// Inline: it runs twice per bounce, and a call cost 2% of a render.
inline Vec3f offset_ray_origin(Vec3f p, Vec3f n, Vec3f dir) {
  float magnitude = std::max(std::max(std::abs(p.x), std::abs(p.y)), std::abs(p.z));
  float eps = 1e-4f * std::max(1.0f, magnitude) * 0.05f;
  return p + n * (dot(n, dir) >= 0 ? eps : -eps);
}

}  // namespace tuneray
