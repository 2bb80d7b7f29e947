// Next-event estimation: picks one light (emissive triangle, point light or the environment)
// with probability proportional to its estimated power, then a point/direction on it (uniform
// over the sphere on a constant environment; the shading step may reshape those by the BSDF,
// QualityOptions::bsdf_sky).
#pragma once

#include <cstdint>
#include <vector>

#include "math/vec.h"
#include "render/environment_light.h"
#include "render/sampling.h"
#include "render/simd8.h"
#include "scene/scene.h"

namespace tuneray {

struct LightSample {
  Vec3f wi;              // from the shading point towards the light (unit)
  float distance = 0;    // to the light point; kInf for the environment
  Color radiance{0.0f};  // incident radiance (area/env) or intensity / distance^2 (point)
  float pdf = 0;         // solid-angle pdf incl. the selection probability; 1 x selection for delta
  bool is_delta = false;
};

// Eight light samples: lane i is what LightSampler::sample gives for lane i's inputs (to float
// rounding); a lane that got no sample has pdf 0.
struct LightSample8 {
  simd::V8 wi;
  simd::F8 distance;
  simd::V8 radiance;
  simd::F8 pdf;
  simd::M8 is_delta;
  // u0 rescaled inside the chosen light's share of [0, 1): the number that placed the sample.
  simd::F8 u_in_light;
};

class LightSampler {
 public:
  LightSampler(const Scene& scene, const EnvironmentLight& environment);

  bool empty() const { return selection_.size() == 0; }
  // u.x picks the light, and u (u.x rescaled inside the light's share of [0, 1)) the point on
  // it, so a sampler's 2D stratification spans the choice of light and the point together.
  LightSample sample(Vec3f p, Vec2f u) const;
  // sample() for the lanes in `lanes` (bit i = lane i) at once: point and triangle lights and a
  // constant environment in SIMD lanes, an environment map lane by lane.
  LightSample8 sample8(const simd::V8& p, simd::F8 u0, simd::F8 u1, uint32_t lanes) const;
  // Solid-angle pdf of having sampled `light_point` on emissive triangle `prim` from p (for MIS
  // when a BSDF-sampled ray hits an emitter).
  float pdf_triangle(uint32_t prim, Vec3f p, Vec3f light_point, Vec3f light_normal) const;
  // The choice among the lights (for tests: bin i is emissive triangle i, then the point
  // lights, then the environment).
  const Distribution1D& selection() const { return selection_; }
  // The probability of choosing the environment (0 without one).
  float environment_pmf() const {
    return env_index_ == SIZE_MAX ? 0.0f : selection_.pmf(env_index_);
  }
  // Radiance leaving an emissive triangle towards `wo` (respects one-sided emission).
  Color emitted(uint32_t prim, Vec3f geometric_normal, Vec3f wo) const;

  size_t emissive_triangle_count() const { return emissive_.size(); }

 private:
  // The triangle's geometry copied next to its area: sampling a light point then reads one
  // record instead of index and vertex arrays, and needs no cross product or square root.
  struct EmissiveTriangle {
    uint32_t prim;
    float area;
    Vec3f p0, edge1, edge2;  // p1 - p0, p2 - p0
    Vec3f normal;            // unit, from the winding
  };
  const Scene& scene_;
  const EnvironmentLight& environment_;
  std::vector<EmissiveTriangle> emissive_;
  // The same lights as planes for sample8's lookups (simd8_lookup.h; zero-padded to whole
  // registers): entry j is selection bin j (triangles and point lights; the environment's bin
  // has zeros). Radiance/intensity include light_scale.
  struct Planes {
    std::vector<float> px, py, pz;     // triangle p0 / point position
    std::vector<float> e1x, e1y, e1z;  // triangle edges (point lights: 0)
    std::vector<float> e2x, e2y, e2z;
    std::vector<float> nx, ny, nz;   // triangle unit normal
    std::vector<float> area;         // triangle area
    std::vector<float> rx, ry, rz;   // emission (triangles) or intensity (points)
    std::vector<int32_t> two_sided;  // -1 (all bits) when the triangle emits on both sides
    std::vector<float> pmf;          // selection probability
    std::vector<float> cdf;          // selection CDF starts: cdf[j] = P(bin < j)
    std::vector<float> cdf_width;    // cdf[j + 1] - cdf[j]
  } planes_;
  std::vector<int32_t> emissive_index_of_prim_;  // -1 when not emissive
  Distribution1D selection_;                     // [emissive..., point lights..., environment]
  size_t point_begin_ = 0, env_index_ = SIZE_MAX;
};

}  // namespace tuneray
