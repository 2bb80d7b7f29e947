#include "render/path_integrator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "render/surface.h"

namespace tuneray {

namespace {
// A frame facing the side of the surface that `wo` is on, so opaque BSDFs (defined on the upper
// hemisphere) work for two-sided geometry. Dielectrics keep the frame: they need the sign.
Frame facing_frame(const SurfaceInteraction& si, Vec3f wo, bool flip, Vec3f* ng) {
  Frame f = si.shading;
  *ng = si.geometric_normal;
  if (flip && dot(*ng, wo) < 0) {
    *ng = -*ng;
    f = Frame(f.s, -f.t, -f.n);
  }
  // Interpolated normals can put wo below the shading hemisphere; the geometric frame is then
  // the better answer than a black pixel.
  if (flip && dot(f.n, wo) <= 1e-6f) f = Frame::from_normal_tangent(*ng, f.s);
  return f;
}

uint64_t now_ns() {
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::steady_clock::now().time_since_epoch())
                                   .count());
}

// Path-space regularization: a lobe may not be sharper than the roughest vertex before it, so
// paths such as diffuse -> mirror -> light become sampleable by light sampling. Lambert counts
// as roughness 1; a mirror behind a rough vertex turns into a GGX conductor of that roughness.
void regularize(BsdfParams& bsdf, float& max_roughness) {
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
}  // namespace

PathIntegrator::PathIntegrator(const Scene& scene, const Accel& accel,
                               const RenderSettings& settings)
    : scene_(scene),
      accel_(accel),
      settings_(settings),
      geometry_(scene),
      environment_(scene.environment,
                   EnvironmentOptions{settings.quality.sky_rgba, settings.quality.lowres_sky}),
      lights_(scene, environment_) {}

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

Color PathIntegrator::radiance(Ray ray, Sampler& sampler, PathCounters& counters,
                               float clamp) const {
  PathState state = start(ray);
  const bool profile = settings_.quality.profile_phases;
  while (state.alive) {
    Hit hit;
    ++counters.rays;
    uint64_t t0 = profile ? now_ns() : 0;
    bool found = accel_.intersect(state.ray, hit);
    if (profile) counters.intersect_ns += now_ns() - t0;
    ShadowRequest shadow;
    shade(state, found, hit, sampler, shadow);
    if (shadow.active) {
      ++counters.shadow_rays;
      t0 = profile ? now_ns() : 0;
      bool blocked = accel_.occluded(shadow.ray);
      if (profile) counters.shadow_ns += now_ns() - t0;
      if (!blocked) state.L += shadow.contribution;
    }
  }
  return finish(state, counters, clamp);
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

void PathIntegrator::shade(PathState& st, bool found, const Hit& hit, Sampler& sampler,
                           ShadowRequest& shadow) const {
  shadow.active = false;
  const bool use_nee = settings_.strategy != LightStrategy::kBsdfOnly;
  const Ray& ray = st.ray;
  if (!found) {
    if (environment_.active()) {
      Color le = environment_radiance(ray.dir, st.specular_chain);
      float w = 1.0f;
      if (!st.previous_was_delta) {
        if (settings_.strategy == LightStrategy::kLightOnly)
          w = 0.0f;
        else if (settings_.strategy == LightStrategy::kMis)
          w = power_heuristic(st.previous_pdf, lights_.pdf_environment(ray.dir));
      }
      (st.specular_chain ? st.L_camera : st.L) += st.beta * le * w;
    }
    st.alive = false;
    return;
  }

  SurfaceInteraction si = geometry_.interaction(hit);
  Vec3f wo_world = -ray.dir;
  if (si.material->is_emissive()) {
    Color le = lights_.emitted(si.prim, si.geometric_normal, wo_world);
    float w = 1.0f;
    if (!st.previous_was_delta) {
      if (settings_.strategy == LightStrategy::kLightOnly)
        w = 0.0f;
      else if (settings_.strategy == LightStrategy::kMis)
        w = power_heuristic(
            st.previous_pdf,
            lights_.pdf_triangle(si.prim, st.previous_position, si.position, si.geometric_normal));
    }
    (st.specular_chain ? st.L_camera : st.L) += st.beta * le * w;
  }
  if (st.depth >= settings_.max_bounces) {
    st.alive = false;
    return;
  }

  BsdfParams bsdf = resolve_bsdf(scene_, si);
  if (settings_.quality.regularize) regularize(bsdf, st.max_roughness);
  const bool opaque = bsdf.type != MaterialType::kDielectric;
  Vec3f ng;
  Frame frame = facing_frame(si, wo_world, opaque, &ng);
  Vec3f wo = frame.to_local(wo_world);

  std::array<float, 4> u_light = sampler.next4();
  std::array<float, 4> u_bsdf = sampler.next4();

  if (use_nee && bsdf_has_smooth_lobe(bsdf) && !lights_.empty()) {
    LightSample ls = lights_.sample(si.position, u_light[0], {u_light[1], u_light[2]});
    if (settings_.quality.lowres_sky && ls.distance >= kInf && ls.pdf > 0)
      ls.radiance = environment_.eval_lowres(ls.wi);
    if (ls.pdf > 0 && max_component(ls.radiance) > 0 && (!opaque || dot(ls.wi, ng) > 0)) {
      Vec3f wi = frame.to_local(ls.wi);
      BsdfEval e = settings_.quality.branchless_materials ? bsdf_evaluate(bsdf, wo, wi)
                                                          : bsdf_evaluate_by_type(bsdf, wo, wi);
      const Color& f = e.f;
      if (max_component(f) > 0) {
        shadow.ray = Ray{};
        shadow.ray.org = offset_ray_origin(si.position, ng, ls.wi);
        shadow.ray.dir = ls.wi;
        shadow.ray.tfar = ls.distance < kInf ? ls.distance * (1.0f - 1e-4f) : kInf;
        float w = 1.0f;
        if (!ls.is_delta && settings_.strategy == LightStrategy::kMis)
          w = power_heuristic(ls.pdf, e.pdf);
        shadow.contribution = st.beta * f * ls.radiance * (std::abs(wi.z) * w / ls.pdf);
        shadow.active = true;
      }
    }
  }

  st.alive = false;
  BsdfSample bs;
  if (!bsdf_sample(bsdf, wo, u_light[3], {u_bsdf[0], u_bsdf[1]}, bs)) return;
  Vec3f wi_world = frame.to_world(bs.wi);
  if (opaque && dot(wi_world, ng) <= 0) return;  // shading normal sent it into the surface
  st.beta *= bs.weight;
  if (!(max_component(st.beta) > 0)) return;
  st.previous_was_delta = bs.is_delta;
  st.specular_chain = st.specular_chain && bs.is_delta;
  st.previous_pdf = bs.pdf;
  st.previous_position = si.position;

  if (st.depth + 1 >= settings_.russian_roulette_depth) {
    float survive = std::min(0.95f, max_component(st.beta));
    if (u_bsdf[2] >= survive) return;
    st.beta *= 1.0f / survive;
  }
  st.ray = Ray{};
  st.ray.org = offset_ray_origin(si.position, ng, wi_world);
  st.ray.dir = wi_world;
  ++st.depth;
  st.alive = true;
}

}  // namespace tuneray
