// Path reuse (QualityOptions::path_reuse; after Bekaert, Sbert and Halton 2002, "Accelerating
// path tracing by re-using paths"). Nearly all of a diffuse scene's noise is in what a path finds
// after its first hit x1 (docs/quality.md, "Thirty-seventh session"): the radiance reflected at its
// second vertex x2 towards x1. Neighbouring pixels' paths sample that same kind of integral from
// nearby first hits, so each pixel of a pool of neighbours estimates its own with every pool
// member's second vertex and the walk beyond it, connected to its x1 by a shadow ray.
//
// Unbiased by multi-sample MIS (balance heuristic): the pool's paths are independent samples x2_j,
// each drawn by its own technique (cosine sampling at x1_j, pdf p_j in area measure, visibility
// included), and pixel i estimates sum_j f_i G_i V_i Lr(x2_j) / sum_k p_k(x2_j). Only Lambertian
// x1 are techniques (their pdf is known in closed form and nothing else changes it), only
// Lambertian x2 are shared (their reflected radiance does not depend on the direction it leaves
// in, so x2_j's walk estimates it towards x1_i too); every other part of a path (its x1's light
// sample, emission hit at x2, misses, glossy or specular x2) stays the path's own.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "accel/accel.h"
#include "math/ray.h"
#include "math/vec.h"
#include "render/sampler.h"

namespace tuneray {

// What the shading step records of a path's first two vertices (per sample slot).
struct ReuseVertices {
  Vec3f p1, n1, ng1;       // first hit, its shading and geometric normals (facing the camera ray)
  Color w1;                // throughput from the camera into x2 (beta x albedo at x1)
  Vec3f p2, ng2, ns2;      // second hit, its geometric and shading normals (facing x1)
  Color l2;                // the path's radiance on arriving at x2, its emission there included
  bool technique = false;  // x1 Lambertian and every channel of w1 > 0: a technique of the pool
  bool shared = false;     // x2 exists and is Lambertian: its reflected radiance is shared
};

// What a technique's pdf and a pixel's integrand share at a pair of vertices, in area measure and
// without visibility and the 1/pi that the Lambertian BSDF and the cosine pdf both carry:
// cos(x1) cos(x2) / r^2 from `from`'s first vertex to `to`'s second. 0 where `from`'s technique
// cannot produce that point (below either normal at x1) or `to`'s walk does not apply (x1 behind
// the side of x2's surface it shaded, or below its shading normal).
float reuse_geometry(const ReuseVertices& from, const ReuseVertices& to);

struct PathReuseScratch {
  std::vector<Ray> rays;
  std::vector<uint8_t> occluded;
  std::vector<uint32_t> from, to;  // slots of a candidate connection x1_from -> x2_to
  std::vector<float> geometry;
  std::vector<float> own;  // per slot: its own technique's geometry, reuse_geometry(v, v)
  std::vector<float> sum;  // per slot: sum over the pool's techniques of geometry x visibility
  std::vector<Color> lr;   // per slot: the reflected radiance at x2 its walk found
  std::vector<Color> gathered;
  std::vector<uint8_t> shares;
};

// The pools of a wave: `ids` lists each pixel's samples one after another (both schedulers'
// order); runs of `pool_pixels` consecutive pixels make a group, and the group's samples of the
// same ordinal within their pixel one pool (a pixel's own samples never share, so its samples
// stay independent, which adaptive sampling's variance estimate needs). Pools of one are left out.
void reuse_pools(std::span<const PixelSampleId> ids, int pool_pixels,
                 std::vector<uint32_t>& pool_slots, std::vector<uint32_t>& pool_begin);

// Replaces the shared part of each path's radiance `indirect[slot]` (what it gathered from x2 on)
// by the pool estimate. `pool_begin` holds offsets into `pool_slots` (pool p is
// pool_slots[pool_begin[p] .. pool_begin[p + 1])). Returns the shadow rays traced.
uint64_t reuse_paths(const Accel& accel, std::span<const uint32_t> pool_slots,
                     std::span<const uint32_t> pool_begin, std::span<const ReuseVertices> vertices,
                     std::span<Color> indirect, PathReuseScratch& scratch);

}  // namespace tuneray
