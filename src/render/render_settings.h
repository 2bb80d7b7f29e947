// Everything that controls how a frame is rendered (not what is rendered).
#pragma once

#include <cstdint>

namespace tuneray {

enum class LightStrategy : uint8_t {
  kMis,        // next-event estimation + BSDF sampling, power heuristic (the default)
  kLightOnly,  // next-event estimation only (emitters hit by BSDF rays count only after deltas)
  kBsdfOnly,   // BSDF sampling only (point lights are then invisible)
};

// Which sample generator a render uses (render/blue_noise_sampler.h: make_sampler).
enum class SamplerKind : uint8_t {
  kPcg,        // independent PCG32 numbers per pixel sample
  kBlueNoise,  // scrambled (0,2)-sequences with blue-noise per-pixel keys; PCG past the tables
               // (the default)
};

// Biased: a path that reaches vertex `vertex` (1 = the second hit) on a Lambertian surface ends
// there into the radiance cache (render/radiance_cache.h) once its cell holds min_samples
// records; a share `train` of those paths goes on and trains the cache with what it finds beyond
// that vertex, as do all paths whose cell is not yet ready.
struct RadianceCacheOptions {
  int vertex = 0;          // 0 = off
  float cell = 1.0f / 16;  // the coarsest cells' side, as a share of the scene's diagonal
  int levels = 2;          // levels of cells, each half the side of the one before
  float train = 0.1f;
  int min_samples = 4;  // records in a coarsest cell (4x that in one a level finer)
};

// The equal-time quality switches (docs/quality.md). Unbiased ones change speed only; the
// biased ones (clamp, regularize, lowres_sky, denoise) must be off for ground-truth renders. The
// defaults are what the ablation in docs/quality.md measured best at equal time (RMSE against
// a converged truth, nine scenes): the wavefront scheduler, blue-noise samples and adaptive
// sampling on; the switches without a measurable gain and the biased ones off.
struct QualityOptions {
  bool wavefront = true;    // waves of paths with batched intersection (else tiles)
  int batch_size = 1024;    // paths per wave (a work size the tuner may pick)
  bool sky_rgba = false;    // environment texels as aligned 16-byte RGBA (else 12-byte RGB)
  bool lowres_sky = false;  // biased: 8x8-averaged sky for rays after the first bounce
  bool regularize = false;  // biased: roughness never below the path's largest so far
  float clamp = 0;          // biased: max length of a path contribution (0 = off)
  // Biased: clamp relative to the image so far, per pixel m = clamp_relative x max(its 3x3
  // neighbourhood's mean pixel length, the image's) (render/firefly_clamp.h; 0 = off; the
  // first pass of a film is unclamped). One setting then fits scenes whose brightness differs
  // by orders of magnitude. `clamp` wins if both are set.
  float clamp_relative = 0;
  bool adaptive = true;         // frame-budget mode: extra samples where the error is highest
  int adaptive_min_spp = 4;     // uniform samples per pixel before the variance is trusted
  bool profile_phases = false;  // time intersection / shading / shadow (costs a little)
  SamplerKind sampler = SamplerKind::kBlueNoise;  // unbiased either way
  bool branchless_materials = false;  // f and pdf in one straight-line pass (bsdf_evaluate)
  // A constant environment's light samples are directions drawn from the BSDF at the shading
  // point (so none fall below the surface), else uniform over the sphere (path_shade8.cpp).
  bool bsdf_sky = true;
  // Biased: what a frame shows is filtered by the edge-avoiding denoiser (render/denoiser.h);
  // the film itself keeps accumulating the unbiased estimate.
  bool denoise = false;
  RadianceCacheOptions cache;  // biased when on
  // Unbiased: pools of this many neighbouring pixels share their paths' second vertices
  // (render/path_reuse.h; 0 or 1 = off). Needs max_bounces and russian_roulette_depth >= 2 and
  // no radiance cache, else it is off.
  int path_reuse = kReusePool;
  // The default pool, and the one `render --path-reuse auto` takes: 8 and 32 measured worse on
  // the pathtracer's Cornell box (docs/quality.md, "Forty-ninth session").
  static constexpr int kReusePool = 16;
  // With path_reuse on: frame-budget rendering (render/frame_budget.h) turns reuse on or off per
  // pass, as its own passes show it lowers the error per unit of time or not
  // (render/reuse_switch.h); passes of a fixed sample count (render --spp, bench render, tune's
  // frames, ground truths) trace without it. False: every pass traces with reuse.
  bool path_reuse_auto = true;

  bool biased() const {
    return lowres_sky || regularize || clamp > 0 || clamp_relative > 0 || denoise ||
           cache.vertex > 0;
  }

  // Every technique off: tiles, 12-byte sky texels, per-type materials, PCG numbers, uniform
  // sampling, a constant sky light-sampled uniformly, no path reuse, nothing biased. The plain
  // renderer that ground truths use and that the ablation measures every technique against.
  static QualityOptions reference() {
    QualityOptions o;
    o.wavefront = o.sky_rgba = o.adaptive = o.branchless_materials = o.bsdf_sky = false;
    o.sampler = SamplerKind::kPcg;
    o.path_reuse = 0;
    o.path_reuse_auto = false;
    return o.without_bias();
  }

  // Every option that changes the expected image switched off, every unbiased one left as it
  // is.
  QualityOptions without_bias() const {
    QualityOptions o = *this;
    o.lowres_sky = o.regularize = o.denoise = false;
    o.clamp = o.clamp_relative = 0;
    o.cache.vertex = 0;
    return o;
  }
};

struct RenderSettings {
  int width = 640;
  int height = 360;
  int max_bounces = 3;             // scattering events per path, as pbrt's maxdepth (1 = direct)
  int russian_roulette_depth = 3;  // bounces before Russian roulette may end a path
  int tile_size = 32;              // pixels per tile side (a work size the tuner may pick)
  uint64_t seed = 0;
  LightStrategy strategy = LightStrategy::kMis;
  QualityOptions quality;
};

}  // namespace tuneray
