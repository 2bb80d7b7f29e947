// The one path tracer: unidirectional, next-event estimation and BSDF sampling combined with
// multiple importance sampling (power heuristic), Russian roulette. It is written as steps on a
// wave of paths (PathWave) so that both schedulers drive the same code: the tile scheduler
// traces a tile's paths one ray at a time, the wavefront scheduler runs each step over a whole
// wave with batched intersection between them; both shade eight paths at a time in SIMD lanes.
// It knows the accelerator only through the Accel interface.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "accel/accel.h"
#include "render/environment_light.h"
#include "render/light_sampler.h"
#include "render/path_wave.h"
#include "render/radiance_cache.h"
#include "render/render_settings.h"
#include "render/reuse_switch.h"
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
  uint64_t total_ns = 0;        // whole path work on this thread (shading = total - the two above)
  uint64_t reused_samples = 0;  // pixel samples traced with path reuse
  ReuseMoments reuse;           // what they tell of its worth (render/reuse_switch.h)
};

// The random numbers of a shading step, in the order a path's sampler hands them out. shade8
// reads them as planes u[0..7] over the wave's positions. Each 2D sample takes a whole pair
// (0, 1), (2, 3), ...: the blue-noise sampler stratifies those pairs jointly, not numbers of two
// different pairs. The 2D samples come first because its tables end after the first four numbers
// of the second bounce, which then go to the next direction and the light.
enum ShadeSample : int {
  kBsdfX,     // the next direction ...
  kBsdfY,     // ... as a 2D sample
  kLightX,    // which light, and (rescaled inside its share) the point on it ...
  kLightY,    // ... as a 2D sample (LightSampler::sample)
  kLobe,      // which BSDF lobe the next direction comes from
  kSkyLobe,   // which lobe shapes a light sample of a constant sky (QualityOptions::bsdf_sky)
  kRoulette,  // Russian roulette
  kSpare,     // unused: the sampler hands numbers out in fours
  kShadeSamples
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

  // The steps. PathWave::start() makes the state of a camera path. shade8() consumes the result
  // of tracing the rays of wave positions [begin, begin + count) (count <= 8) to hits[0..count)
  // (invalid: a miss): it adds emission, samples a light and the next direction. It returns the
  // lanes (bit i = position begin + i) whose path goes on, with its next ray in the wave; the
  // others end here. shadow[i] says whether lane i needs a shadow ray. u[k][j] is the path at
  // position j's k-th number of the step, read only where needs_samples. finish() is a path's
  // value: NaN/inf dropped; with a firefly clamp m > 0, everything but what the camera sees
  // directly is clamped to length m.
  uint32_t shade8(PathWave& wave, size_t begin, int count, const Hit* hits, const float* const* u,
                  ShadowRequest* shadow) const;
  // Whether shade8() will use a path's numbers: it hit something and may still scatter. A path
  // that does not ends in this step, so it would never draw them.
  bool needs_samples(const PathWave& wave, size_t i, bool found) const {
    return found && wave.depth[i] < settings_.max_bounces;
  }
  Color finish(const PathWave& wave, size_t i, PathCounters& counters, float clamp) const {
    return finish(wave.radiance(i), wave.camera_radiance(i), counters, clamp);
  }
  // The same from a path's two parts (PathWave::radiance and camera_radiance), for a scheduler
  // that changes the first before the path's value is taken (path reuse).
  Color finish(Color indirect, Color camera, PathCounters& counters, float clamp) const;
  // Pixels per path-reuse pool (path_reuse.h), 0 when reuse is off: it is on for pools of two or
  // more, paths that scatter at least twice, no Russian roulette at the first hit (its pdf
  // would change the technique's) and no radiance cache (whose paths end at the second hit).
  int reuse_pool_pixels() const {
    const QualityOptions& q = settings_.quality;
    return q.path_reuse >= 2 && settings_.max_bounces >= 2 &&
                   settings_.russian_roulette_depth >= 2 && q.cache.vertex == 0
               ? q.path_reuse
               : 0;
  }
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

  // The radiance cache that paths end into at settings().quality.cache.vertex (null: none). Read
  // by shade8, so it must not change while a pass runs; the paths that train it are marked in the
  // wave (PathWave::cache_key) and the scheduler hands their records to it between passes.
  void use_radiance_cache(const RadianceCache* cache) { cache_ = cache; }
  const RadianceCache* radiance_cache() const { return cache_; }

  const LightSampler& lights() const { return lights_; }
  const Accel& accel() const { return accel_; }
  const RenderSettings& settings() const { return settings_; }

 private:
  Color environment_radiance(const EnvironmentLookup& at, bool specular_chain) const;
  // The per-lane parts of shade8: a path whose ray left the scene (it ends), and the emission of
  // an emitter the ray hit, weighted against light sampling.
  void shade_miss(PathWave& wave, size_t i) const;
  // shade_miss for the lanes of positions [begin, begin + 8) in `missed`, when the environment
  // is constant (or absent).
  void shade_misses(PathWave& wave, size_t begin, simd::M8 missed) const;
  void add_emission(PathWave& wave, size_t i, const Hit& hit) const;

  // The materials as planes for shade8's lookups (index: material id; zero-padded to whole
  // registers, simd8_lookup.h).
  struct MaterialPlanes {
    std::vector<int32_t> type;  // MaterialType
    std::vector<float> base_r, base_g, base_b, specular_r, specular_g, specular_b;
    std::vector<float> alpha_x, alpha_y;
    std::vector<uint8_t> emissive, textured;
  };

  const Scene& scene_;
  const Accel& accel_;
  RenderSettings settings_;
  ShadingGeometry geometry_;
  EnvironmentLight environment_;
  LightSampler lights_;
  std::vector<BsdfParams> material_bsdf_;  // untextured_bsdf of each scene material
  MaterialPlanes material_planes_;
  const RadianceCache* cache_ = nullptr;
};

}  // namespace tuneray
