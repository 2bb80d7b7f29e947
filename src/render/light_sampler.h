// Next-event estimation: picks one light (emissive triangle, point light or the environment)
// with probability proportional to its estimated power, then a point/direction on it.
#pragma once

#include <cstdint>
#include <vector>

#include "math/vec.h"
#include "render/environment_light.h"
#include "render/sampling.h"
#include "scene/scene.h"

namespace tuneray {

struct LightSample {
  Vec3f wi;              // from the shading point towards the light (unit)
  float distance = 0;    // to the light point; kInf for the environment
  Color radiance{0.0f};  // incident radiance (area/env) or intensity / distance^2 (point)
  float pdf = 0;         // solid-angle pdf incl. the selection probability; 1 x selection for delta
  bool is_delta = false;
};

class LightSampler {
 public:
  LightSampler(const Scene& scene, const EnvironmentLight& environment);

  bool empty() const { return selection_.size() == 0; }
  // u_select picks the light, u the point on it.
  LightSample sample(Vec3f p, float u_select, Vec2f u) const;
  // Solid-angle pdf of having sampled `light_point` on emissive triangle `prim` from p (for MIS
  // when a BSDF-sampled ray hits an emitter).
  float pdf_triangle(uint32_t prim, Vec3f p, Vec3f light_point, Vec3f light_normal) const;
  float pdf_environment(Vec3f dir) const;
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
  std::vector<int32_t> emissive_index_of_prim_;  // -1 when not emissive
  Distribution1D selection_;                     // [emissive..., point lights..., environment]
  size_t point_begin_ = 0, env_index_ = SIZE_MAX;
};

}  // namespace tuneray
