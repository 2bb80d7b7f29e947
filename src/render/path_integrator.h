// The one path tracer: unidirectional, next-event estimation and BSDF sampling combined with
// multiple importance sampling (power heuristic), Russian roulette. It is written as steps on a
// PathState so that both schedulers drive the same code: the tile scheduler runs the steps of
// one path back to back (radiance()), the wavefront scheduler runs each step over a whole wave
// of paths with batched intersection between them. It knows the accelerator only through the
// Accel interface.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

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

// The random numbers one shade() step consumes: a light sample and a BSDF sample. A scheduler
// draws them (only for a path that needs_samples) and hands them over, so that a batch scheduler
// can draw a whole wave's numbers at once.
struct ShadeSamples {
  std::array<float, 4> light, bsdf;
};
static_assert(sizeof(ShadeSamples) == 8 * sizeof(float));

// A next-event-estimation ray; `contribution` is added to L when it is not occluded.
struct ShadowRequest {
  Ray ray;
  Color contribution{0.0f};
  bool active = false;
};

// Up to eight paths shaded together by PathIntegrator::shade8: lane i is path *state[i], which
// traced state[i]->ray to `hit[i]` (invalid: a miss), with the numbers u[i] (read only when
// needs_samples); shade8 fills shadow[i].
struct ShadeBatch {
  int count = 0;
  PathState* state[8];
  Hit hit[8];
  ShadeSamples u[8];
  ShadowRequest shadow[8];
};

class PathIntegrator {
 public:
  PathIntegrator(const Scene& scene, const Accel& accel, const RenderSettings& settings);

  // Radiance arriving along up to eight camera rays, traced one ray at a time through the
  // accelerator's single-ray calls (the tile scheduler); each path's steps run back to back with
  // the other lanes', out[i] its sample value. `samplers[i]` must be positioned at the lane's
  // pixel sample (after the camera's four numbers). `clamp[i]` is the firefly clamp m of lane i
  // (0 = off); the scheduler resolves it per pass (TileRenderer::clamp_for), since a relative
  // clamp depends on the image so far.
  void radiance8(const Ray* camera_rays, Sampler* const* samplers, const float* clamp, int count,
                 PathCounters& counters, Color* out) const;

  // The steps. start() makes the state of a camera path. shade8() consumes the result of
  // tracing each lane's ray (a hit or a miss), adds emission, samples a light and the next
  // direction: afterwards state.ray is the next ray or state.alive is false, and the lane's
  // ShadowRequest says whether a shadow ray must be traced. finish() is the sample's value:
  // NaN/inf dropped; with a firefly clamp m > 0, everything but what the camera sees directly is
  // clamped to length m.
  static PathState start(const Ray& camera_ray);
  // Whether shade8() will use a lane's ShadeSamples: a path that hit something and may still
  // scatter. A path that does not ends in this step, so it would never draw those numbers.
  bool needs_samples(const PathState& state, bool found) const {
    return found && state.depth < settings_.max_bounces;
  }
  void shade8(ShadeBatch& batch) const;
  Color finish(const PathState& state, PathCounters& counters, float clamp) const;
  // Prefetches, in two steps, what shade8() will read about a hit (surface.h); a batch scheduler
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
  // The per-lane parts of shade8: a path whose ray left the scene (it ends), and the emission of
  // an emitter the ray hit, weighted against light sampling.
  void shade_miss(PathState& state) const;
  void add_emission(PathState& state, const Hit& hit) const;
  // Path-space regularization (quality.regularize).
  static void regularize(BsdfParams& bsdf, float& max_roughness);

  const Scene& scene_;
  const Accel& accel_;
  RenderSettings settings_;
  ShadingGeometry geometry_;
  EnvironmentLight environment_;
  LightSampler lights_;
  std::vector<BsdfParams> material_bsdf_;  // untextured_bsdf of each scene material
};

}  // namespace tuneray
