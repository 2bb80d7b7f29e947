#include "render/denoiser_features.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "render/surface.h"

namespace tuneray {

namespace {

// Mirrors followed before a mirror's own colour is taken (a hall of mirrors must end).
constexpr int kMaxMirrorBounces = 4;

// What the surface does to light, as one colour: its reflectance at normal incidence, roughly.
Color albedo_of(const BsdfParams& b) {
  switch (b.type) {
    case MaterialType::kLambert:
      return b.base_color;
    case MaterialType::kGlossy:
    case MaterialType::kMirror:
      return b.specular_color;
    case MaterialType::kPrincipled: {
      float coat = std::clamp(max_component(b.specular_color), 0.0f, 1.0f);
      return b.base_color * (1.0f - coat) + b.specular_color;
    }
    case MaterialType::kDielectric:
      break;
  }
  return Color(1.0f);
}

struct Feature {
  Color albedo{0.0f};
  Vec3f normal{0.0f};
  bool emitter = false;
};

Feature trace_feature(const Scene& scene, const Accel& accel, Ray ray) {
  Color tint(1.0f);
  for (int bounce = 0;; ++bounce) {
    Hit hit;
    if (!accel.intersect(ray, hit)) return {tint, -ray.dir};
    SurfaceInteraction si = make_interaction(scene, hit);
    Vec3f n = si.shading.n;
    if (dot(n, ray.dir) > 0) n = -n;
    if (si.material->is_emissive()) return {tint, n, true};
    BsdfParams bsdf = resolve_bsdf(scene, si);
    if (bsdf.type != MaterialType::kMirror || bounce == kMaxMirrorBounces)
      return {tint * albedo_of(bsdf), n};
    tint *= bsdf.specular_color;
    Vec3f ng = dot(si.geometric_normal, ray.dir) > 0 ? -si.geometric_normal : si.geometric_normal;
    Vec3f reflected = ray.dir - n * (2.0f * dot(ray.dir, n));
    if (dot(reflected, ng) <= 0) return {tint, n};  // the shading normal sent it inside
    Ray next;
    next.org = offset_ray_origin(si.position, ng, reflected);
    next.dir = reflected;
    ray = next;
  }
}

}  // namespace

DenoiseFeatures render_denoise_features(const TileRenderer& renderer) {
  const RenderSettings& s = renderer.settings();
  const Scene& scene = renderer.scene();
  const Accel& accel = renderer.integrator().accel();
  const Camera& camera = renderer.camera();
  DenoiseFeatures f;
  f.width = s.width;
  f.height = s.height;
  const size_t pixels = static_cast<size_t>(s.width) * s.height;
  f.albedo.assign(pixels, Color(0.0f));
  f.normal.assign(pixels, Vec3f(0.0f));
  f.emitter.assign(pixels, 0);
  constexpr int kSide = kFeatureRaysPerSide;
  constexpr float kWeight = 1.0f / (kSide * kSide);
  tbb::parallel_for(tbb::blocked_range<int>(0, s.height), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y)
      for (int x = 0; x < s.width; ++x) {
        Color albedo(0.0f);
        Vec3f normal(0.0f);
        bool emitter = false;
        for (int j = 0; j < kSide; ++j)
          for (int i = 0; i < kSide; ++i) {
            Vec2f at{x + (i + 0.5f) / kSide, y + (j + 0.5f) / kSide};
            Feature one = trace_feature(scene, accel, camera.generate_ray(at, {0.5f, 0.5f}));
            albedo += one.albedo * kWeight;
            normal += one.normal;
            emitter = emitter || one.emitter;
          }
        size_t p = static_cast<size_t>(y) * s.width + x;
        f.albedo[p] = albedo;
        f.emitter[p] = emitter;
        float len = length(normal);
        // Opposite normals in one pixel (a thin sheet's edge) cancel: any unit vector will do.
        f.normal[p] = len > 1e-6f ? normal / len : Vec3f(0.0f, 0.0f, 1.0f);
      }
  });
  return f;
}

}  // namespace tuneray
