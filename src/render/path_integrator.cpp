#include "render/path_integrator.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "render/simd8_lookup.h"
#include "render/surface.h"

namespace tuneray {

PathIntegrator::PathIntegrator(const Scene& scene, const Accel& accel,
                               const RenderSettings& settings)
    : scene_(scene),
      accel_(accel),
      settings_(settings),
      geometry_(scene),
      environment_(scene.environment,
                   EnvironmentOptions{settings.quality.sky_rgba, settings.quality.lowres_sky}),
      lights_(scene, environment_) {
  material_bsdf_.reserve(scene.materials.size());
  for (const Material& m : scene.materials) material_bsdf_.push_back(untextured_bsdf(m));
  MaterialPlanes& mp = material_planes_;
  for (const BsdfParams& p : material_bsdf_) {
    mp.type.push_back(static_cast<int32_t>(p.type));
    mp.base_r.push_back(p.base_color.x);
    mp.base_g.push_back(p.base_color.y);
    mp.base_b.push_back(p.base_color.z);
    mp.specular_r.push_back(p.specular_color.x);
    mp.specular_g.push_back(p.specular_color.y);
    mp.specular_b.push_back(p.specular_color.z);
    mp.alpha_x.push_back(p.alpha_x);
    mp.alpha_y.push_back(p.alpha_y);
  }
  // Padded for shade8's lookups (simd8_lookup.h).
  simd::pad_for_lookup(mp.type);
  for (auto* plane : {&mp.base_r, &mp.base_g, &mp.base_b, &mp.specular_r, &mp.specular_g,
                      &mp.specular_b, &mp.alpha_x, &mp.alpha_y})
    simd::pad_for_lookup(*plane);
  for (const Material& m : scene.materials) {
    mp.emissive.push_back(m.is_emissive() ? 1 : 0);
    mp.textured.push_back(m.base_texture != kNoTexture ? 1 : 0);
  }
}

Color PathIntegrator::environment_radiance(const EnvironmentLookup& at, bool specular_chain) const {
  // Low-resolution sky after a rough bounce, which blurs it anyway; the sky the camera sees
  // directly or in a mirror or through glass stays sharp.
  return settings_.quality.lowres_sky && !specular_chain ? environment_.eval_lowres(at)
                                                         : environment_.eval(at);
}

Color PathIntegrator::finish(Color indirect, Color camera, PathCounters& counters,
                             float clamp) const {
  if (!is_finite(indirect) || !is_finite(camera)) {
    ++counters.invalid_samples;
    return Color(0.0f);
  }
  // Emitters seen directly are not fireflies; clamping them would darken every visible light.
  if (clamp > 0) {
    float len = length(indirect);
    if (len > clamp) indirect *= clamp / len;
  }
  return camera + indirect;
}

namespace {
// Where a path adds what it sees: to the camera part while every vertex was specular.
void add_seen(PathWave& wave, size_t i, Color c) {
  const int base = wave.flags[i] & PathWave::kSpecularChain ? PathWave::kCameraX : PathWave::kLX;
  wave.plane(base)[i] += c.x;
  wave.plane(base + 1)[i] += c.y;
  wave.plane(base + 2)[i] += c.z;
}
Color beta_of(const PathWave& wave, size_t i) {
  return {wave.plane(PathWave::kBetaX)[i], wave.plane(PathWave::kBetaY)[i],
          wave.plane(PathWave::kBetaZ)[i]};
}
}  // namespace

void PathIntegrator::shade_miss(PathWave& wave, size_t i) const {
  if (!environment_.active()) return;
  const EnvironmentLookup at = EnvironmentLight::locate(wave.ray(i).dir);
  const bool specular_chain = wave.flags[i] & PathWave::kSpecularChain;
  Color le = environment_radiance(at, specular_chain);
  float w = 1.0f;
  if (!(wave.flags[i] & PathWave::kPreviousWasDelta)) {
    if (settings_.strategy == LightStrategy::kLightOnly)
      w = 0.0f;
    else if (settings_.strategy == LightStrategy::kMis)
      w = power_heuristic(wave.plane(PathWave::kPrevPdf)[i],
                          lights_.environment_pmf() * environment_.pdf(at));
  }
  add_seen(wave, i, beta_of(wave, i) * le * w);
}

void PathIntegrator::add_emission(PathWave& wave, size_t i, const Hit& hit) const {
  const SurfaceInteraction si = geometry_.interaction(hit);
  Color le = lights_.emitted(si.prim, si.geometric_normal, -wave.ray(i).dir);
  float w = 1.0f;
  if (!(wave.flags[i] & PathWave::kPreviousWasDelta)) {
    if (settings_.strategy == LightStrategy::kLightOnly) {
      w = 0.0f;
    } else if (settings_.strategy == LightStrategy::kMis) {
      const Vec3f previous{wave.plane(PathWave::kPrevX)[i], wave.plane(PathWave::kPrevY)[i],
                           wave.plane(PathWave::kPrevZ)[i]};
      w = power_heuristic(
          wave.plane(PathWave::kPrevPdf)[i],
          lights_.pdf_triangle(si.prim, previous, si.position, si.geometric_normal));
    }
  }
  add_seen(wave, i, beta_of(wave, i) * le * w);
}

}  // namespace tuneray
