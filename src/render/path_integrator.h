// The one path tracer: unidirectional, next-event estimation and BSDF sampling combined with
// multiple importance sampling (power heuristic), Russian roulette. The tile and wavefront
// schedulers both call it; it knows the accelerator only through the Accel interface.
#pragma once

#include <cstdint>

#include "accel/accel.h"
#include "render/environment_light.h"
#include "render/light_sampler.h"
#include "render/render_settings.h"
#include "render/sampler.h"
#include "scene/scene.h"

namespace tuneray {

struct PathCounters {
  uint64_t rays = 0;             // closest-hit rays
  uint64_t shadow_rays = 0;      // any-hit rays
  uint64_t invalid_samples = 0;  // NaN/inf radiance dropped
};

class PathIntegrator {
 public:
  PathIntegrator(const Scene& scene, const Accel& accel, const RenderSettings& settings);

  // Radiance arriving along `ray` (a camera ray).
  Color radiance(Ray ray, Sampler& sampler, PathCounters& counters) const;

  const LightSampler& lights() const { return lights_; }

 private:
  const Scene& scene_;
  const Accel& accel_;
  RenderSettings settings_;
  EnvironmentLight environment_;
  LightSampler lights_;
};

}  // namespace tuneray
