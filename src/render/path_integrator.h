// The one path tracer: unidirectional, next-event estimation and BSDF sampling combined with
// multiple importance sampling (power heuristic), Russian roulette. It is written as steps on a
// PathState so that both schedulers drive the same code: the tile scheduler runs the steps of
// one path back to back (radiance()), the wavefront scheduler runs each step over a whole wave
// of paths with batched intersection between them. It knows the accelerator only through the
// Accel interface.
#pragma once

#include <cstdint>

#include "accel/accel.h"
#include "render/environment_light.h"
#include "render/light_sampler.h"
#include "render/render_settings.h"
#include "render/sampler.h"
#include "render/shading_geometry.h"
#include "render/surface.h"
#include "scene/scene.h"

namespace tuneray {

struct PathCounters {
  uint64_t rays = 0;             // closest-hit rays
  uint64_t shadow_rays = 0;      // any-hit rays
  uint64_t invalid_samples = 0;  // NaN/inf radiance dropped
  // Phase clocks (steady_clock nanoseconds), only filled when quality.profile_phases is on.
  uint64_t intersect_ns = 0;
  uint64_t shadow_ns = 0;
  uint64_t total_ns = 0;  // whole path work on this thread (shading = total - the two above)
};

// One path between two steps: the ray to trace next and what the path has gathered.
struct PathState {
  Ray ray;
  Color L{0.0f};
  // Emission the camera sees directly or through specular (delta) vertices only, e.g. a lamp
  // reflected in water: part of the visible scene, not a firefly, so never clamped.
  Color L_camera{0.0f};
  Color beta{1.0f};
  Vec3f previous_position;
  float previous_pdf = 0;
  float max_roughness = 0;  // largest roughness seen so far (path-space regularization)
  int depth = 0;            // index of the vertex `ray` will hit (0 = camera ray)
  bool previous_was_delta = true;
  bool specular_chain = true;  // every vertex so far was specular (the camera ray counts)
  bool alive = true;
};

// A next-event-estimation ray; `contribution` is added to L when it is not occluded.
struct ShadowRequest {
  Ray ray;
  Color contribution{0.0f};
  bool active = false;
};

class PathIntegrator {
 public:
  PathIntegrator(const Scene& scene, const Accel& accel, const RenderSettings& settings);

  // Radiance arriving along `ray` (a camera ray): the steps below run back to back. `clamp` is
  // the firefly clamp m for this sample (0 = off); the scheduler resolves it per pass
  // (TileRenderer::clamp_for), since a relative clamp depends on the image so far.
  Color radiance(Ray ray, Sampler& sampler, PathCounters& counters, float clamp) const;

  // The steps. start() makes the state of a camera path. shade() consumes the result of
  // tracing state.ray (found/hit), adds emission, samples a light and the next direction:
  // afterwards state.ray is the next ray or state.alive is false, and `shadow` says whether a
  // shadow ray must be traced. finish() is the sample's value: NaN/inf dropped; with a firefly
  // clamp m > 0, everything but what the camera sees directly is clamped to length m.
  static PathState start(const Ray& camera_ray);
  void shade(PathState& state, bool found, const Hit& hit, Sampler& sampler,
             ShadowRequest& shadow) const;
  Color finish(const PathState& state, PathCounters& counters, float clamp) const;
  // Prefetches, in two steps, what shade() will read about a hit (surface.h); a batch scheduler
  // calls step 0 far ahead and step 1 nearer.
  void prefetch_hit(const Hit& hit, int step) const {
    if (!hit.valid()) return;
    if (step == 0) {
      prefetch_hit_triangle(scene_, hit.prim);
      geometry_.prefetch(hit.prim);
    } else
      prefetch_hit_vertices(scene_, hit.prim);
  }

  const LightSampler& lights() const { return lights_; }
  const Accel& accel() const { return accel_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  Color environment_radiance(Vec3f dir, bool specular_chain) const;

  const Scene& scene_;
  const Accel& accel_;
  RenderSettings settings_;
  ShadingGeometry geometry_;
  EnvironmentLight environment_;
  LightSampler lights_;
};

}  // namespace tuneray
