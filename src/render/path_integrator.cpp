#include "render/path_integrator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "render/surface.h"

namespace tuneray {

namespace {
uint64_t now_ns() {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::steady_clock::now().time_since_epoch())
                                   .count());
}
}  // namespace

// A lobe may not be sharper than the roughest vertex before it, so paths such as diffuse ->
// mirror -> light become sampleable by light sampling. Lambert counts as roughness 1; a mirror
// behind a rough vertex turns into a GGX conductor of that roughness.
void PathIntegrator::regularize(BsdfParams& bsdf, float& max_roughness) {
  float own = 0;
  switch (bsdf.type) {
    case MaterialType::kLambert:
      own = 1.0f;
      break;
    case MaterialType::kGlossy:
    case MaterialType::kPrincipled:
      bsdf.alpha_x = std::max(bsdf.alpha_x, max_roughness);
      bsdf.alpha_y = std::max(bsdf.alpha_y, max_roughness);
      own = std::max(bsdf.alpha_x, bsdf.alpha_y);
      break;
    case MaterialType::kMirror:
      if (max_roughness > 0) {
        bsdf.type = MaterialType::kGlossy;
        bsdf.alpha_x = bsdf.alpha_y = max_roughness;
        own = max_roughness;
      }
      break;
    case MaterialType::kDielectric:
      break;  // no rough dielectric lobe to widen into
  }
  max_roughness = std::max(max_roughness, own);
}

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
}

Color PathIntegrator::environment_radiance(Vec3f dir, bool specular_chain) const {
  // Low-resolution sky after a rough bounce, which blurs it anyway; the sky the camera sees
  // directly or in a mirror or through glass stays sharp.
  return settings_.quality.lowres_sky && !specular_chain ? environment_.eval_lowres(dir)
                                                         : environment_.eval(dir);
}

PathState PathIntegrator::start(const Ray& camera_ray) {
  PathState s;
  s.ray = camera_ray;
  s.previous_position = camera_ray.org;
  return s;
}

void PathIntegrator::radiance8(const Ray* camera_rays, Sampler* const* samplers, const float* clamp,
                               int count, PathCounters& counters, Color* out) const {
  PathState states[8];
  ShadeBatch batch;
  int lane_of[8];
  for (int i = 0; i < count; ++i) states[i] = start(camera_rays[i]);
  const bool profile = settings_.quality.profile_phases;
  for (;;) {
    batch.count = 0;
    for (int i = 0; i < count; ++i) {
      if (!states[i].alive) continue;
      const int k = batch.count++;
      lane_of[k] = i;
      batch.state[k] = &states[i];
      Hit& hit = batch.hit[k];
      hit = Hit{};
      ++counters.rays;
      uint64_t t0 = profile ? now_ns() : 0;
      accel_.intersect(states[i].ray, hit);
      if (profile) counters.intersect_ns += now_ns() - t0;
      if (needs_samples(states[i], hit.valid())) {
        batch.u[k].light = samplers[i]->next4();
        batch.u[k].bsdf = samplers[i]->next4();
      }
    }
    if (batch.count == 0) break;
    shade8(batch);
    for (int k = 0; k < batch.count; ++k) {
      const ShadowRequest& shadow = batch.shadow[k];
      if (!shadow.active) continue;
      ++counters.shadow_rays;
      uint64_t t0 = profile ? now_ns() : 0;
      bool blocked = accel_.occluded(shadow.ray);
      if (profile) counters.shadow_ns += now_ns() - t0;
      if (!blocked) states[lane_of[k]].L += shadow.contribution;
    }
  }
  for (int i = 0; i < count; ++i) out[i] = finish(states[i], counters, clamp[i]);
}

Color PathIntegrator::finish(const PathState& state, PathCounters& counters, float clamp) const {
  Color indirect = state.L;
  if (!is_finite(indirect) || !is_finite(state.L_camera)) {
    ++counters.invalid_samples;
    return Color(0.0f);
  }
  // Emitters seen directly are not fireflies; clamping them would darken every visible light.
  if (clamp > 0) {
    float len = length(indirect);
    if (len > clamp) indirect *= clamp / len;
  }
  return state.L_camera + indirect;
}

void PathIntegrator::shade_miss(PathState& st) const {
  if (environment_.active()) {
    Color le = environment_radiance(st.ray.dir, st.specular_chain);
    float w = 1.0f;
    if (!st.previous_was_delta) {
      if (settings_.strategy == LightStrategy::kLightOnly)
        w = 0.0f;
      else if (settings_.strategy == LightStrategy::kMis)
        w = power_heuristic(st.previous_pdf, lights_.pdf_environment(st.ray.dir));
    }
    (st.specular_chain ? st.L_camera : st.L) += st.beta * le * w;
  }
  st.alive = false;
}

void PathIntegrator::add_emission(PathState& st, const Hit& hit) const {
  const SurfaceInteraction si = geometry_.interaction(hit);
  Color le = lights_.emitted(si.prim, si.geometric_normal, -st.ray.dir);
  float w = 1.0f;
  if (!st.previous_was_delta) {
    if (settings_.strategy == LightStrategy::kLightOnly)
      w = 0.0f;
    else if (settings_.strategy == LightStrategy::kMis)
      w = power_heuristic(st.previous_pdf, lights_.pdf_triangle(si.prim, st.previous_position,
                                                                si.position, si.geometric_normal));
  }
  (st.specular_chain ? st.L_camera : st.L) += st.beta * le * w;
}

}  // namespace tuneray
