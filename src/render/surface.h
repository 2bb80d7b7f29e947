// What the integrator knows about a hit: position, normals, shading frame, UV, material.
#pragma once

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

SurfaceInteraction make_interaction(const Scene& scene, const Hit& hit);

// Resolves textures: the BSDF parameters at this point.
BsdfParams resolve_bsdf(const Scene& scene, const SurfaceInteraction& si);

// Origin for a ray leaving `p` towards side `dir` of the surface with geometric normal n:
// offset along n by an amount that scales with the coordinates' magnitude (float precision).
Vec3f offset_ray_origin(Vec3f p, Vec3f n, Vec3f dir);

}  // namespace tuneray
