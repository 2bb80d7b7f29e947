#include "render/path_integrator.h"

#include <array>
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
}  // namespace

PathIntegrator::PathIntegrator(const Scene& scene, const Accel& accel,
                               const RenderSettings& settings)
    : scene_(scene),
      accel_(accel),
      settings_(settings),
      environment_(scene.environment),
      lights_(scene, environment_) {}

Color PathIntegrator::radiance(Ray ray, Sampler& sampler, PathCounters& counters) const {
  Color L(0.0f), beta(1.0f);
  bool previous_was_delta = true;  // the camera: count what it sees directly
  float previous_pdf = 0;
  Vec3f previous_position = ray.org;
  const bool use_nee = settings_.strategy != LightStrategy::kBsdfOnly;

  for (int depth = 0;; ++depth) {
    Hit hit;
    ++counters.rays;
    if (!accel_.intersect(ray, hit)) {
      if (environment_.active()) {
        Color le = environment_.eval(ray.dir);
        float w = 1.0f;
        if (!previous_was_delta) {
          if (settings_.strategy == LightStrategy::kLightOnly)
            w = 0.0f;
          else if (settings_.strategy == LightStrategy::kMis)
            w = power_heuristic(previous_pdf, lights_.pdf_environment(ray.dir));
        }
        L += beta * le * w;
      }
      break;
    }

    SurfaceInteraction si = make_interaction(scene_, hit);
    Vec3f wo_world = -ray.dir;
    if (si.material->is_emissive()) {
      Color le = lights_.emitted(si.prim, si.geometric_normal, wo_world);
      float w = 1.0f;
      if (!previous_was_delta) {
        if (settings_.strategy == LightStrategy::kLightOnly)
          w = 0.0f;
        else if (settings_.strategy == LightStrategy::kMis)
          w = power_heuristic(previous_pdf, lights_.pdf_triangle(si.prim, previous_position,
                                                                 si.position, si.geometric_normal));
      }
      L += beta * le * w;
    }
    if (depth >= settings_.max_bounces) break;

    BsdfParams bsdf = resolve_bsdf(scene_, si);
    const bool opaque = bsdf.type != MaterialType::kDielectric;
    Vec3f ng;
    Frame frame = facing_frame(si, wo_world, opaque, &ng);
    Vec3f wo = frame.to_local(wo_world);

    std::array<float, 4> u_light = sampler.next4();
    std::array<float, 4> u_bsdf = sampler.next4();

    if (use_nee && bsdf_has_smooth_lobe(bsdf) && !lights_.empty()) {
      LightSample ls = lights_.sample(si.position, u_light[0], {u_light[1], u_light[2]});
      if (ls.pdf > 0 && max_component(ls.radiance) > 0 && (!opaque || dot(ls.wi, ng) > 0)) {
        Vec3f wi = frame.to_local(ls.wi);
        Color f = bsdf_eval(bsdf, wo, wi);
        if (max_component(f) > 0) {
          Ray shadow;
          shadow.org = offset_ray_origin(si.position, ng, ls.wi);
          shadow.dir = ls.wi;
          shadow.tfar = ls.distance < kInf ? ls.distance * (1.0f - 1e-4f) : kInf;
          ++counters.shadow_rays;
          if (!accel_.occluded(shadow)) {
            float w = 1.0f;
            if (!ls.is_delta && settings_.strategy == LightStrategy::kMis)
              w = power_heuristic(ls.pdf, bsdf_pdf(bsdf, wo, wi));
            L += beta * f * ls.radiance * (std::abs(wi.z) * w / ls.pdf);
          }
        }
      }
    }

    BsdfSample bs;
    if (!bsdf_sample(bsdf, wo, u_light[3], {u_bsdf[0], u_bsdf[1]}, bs)) break;
    Vec3f wi_world = frame.to_world(bs.wi);
    if (opaque && dot(wi_world, ng) <= 0) break;  // shading normal sent it into the surface
    beta *= bs.weight;
    if (!(max_component(beta) > 0)) break;
    previous_was_delta = bs.is_delta;
    previous_pdf = bs.pdf;
    previous_position = si.position;

    if (depth + 1 >= settings_.russian_roulette_depth) {
      float survive = std::min(0.95f, max_component(beta));
      if (u_bsdf[2] >= survive) break;
      beta *= 1.0f / survive;
    }
    ray = Ray{};
    ray.org = offset_ray_origin(si.position, ng, wi_world);
    ray.dir = wi_world;
  }

  if (!is_finite(L)) {
    ++counters.invalid_samples;
    return Color(0.0f);
  }
  return L;
}

}  // namespace tuneray
