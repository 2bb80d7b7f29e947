#include "render/denoiser_features.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "math/rng.h"
#include "render/light_sampler.h"
#include "render/surface.h"

namespace tuneray {

namespace {

// Mirrors followed before a mirror's own colour is taken (a hall of mirrors must end).
constexpr int kMaxMirrorBounces = 4;
// How far along the ray the sky's position guide lies, in scene diameters: far enough that the
// sky is never mistaken for a surface's plane, near enough for float differences.
constexpr float kSkyDistance = 1e3f;

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
  // A surface that reflects light (not sky, a light or glass): its direct light's visibility
  // is a guide there. `position` (far along the ray for the sky) is the plane guide's point;
  // with `geometric_normal` (facing the viewer) it places a lit surface's shadow rays.
  bool lit_surface = false;
  Vec3f position{0.0f}, geometric_normal{0.0f};
  bool sky = false;
};

Feature trace_feature(const Scene& scene, const Accel& accel, Ray ray, float sky_distance) {
  Color tint(1.0f);
  for (int bounce = 0;; ++bounce) {
    Hit hit;
    if (!accel.intersect(ray, hit))
      return {tint, -ray.dir, false, false, ray.org + ray.dir * sky_distance, Vec3f(0.0f), true};
    SurfaceInteraction si = make_interaction(scene, hit);
    Vec3f n = si.shading.n;
    if (dot(n, ray.dir) > 0) n = -n;
    if (si.material->is_emissive()) return {tint, n, true, false, si.position};
    BsdfParams bsdf = resolve_bsdf(scene, si);
    Vec3f ng = dot(si.geometric_normal, ray.dir) > 0 ? -si.geometric_normal : si.geometric_normal;
    if (bsdf.type != MaterialType::kMirror || bounce == kMaxMirrorBounces)
      return {tint * albedo_of(bsdf),
              n,
              false,
              bsdf.type != MaterialType::kDielectric,
              si.position,
              ng};
    tint *= bsdf.specular_color;
    Vec3f reflected = ray.dir - n * (2.0f * dot(ray.dir, n));
    if (dot(reflected, ng) <= 0)  // the shading normal sent it inside
      return {tint, n, false, false, si.position};
    Ray next;
    next.org = offset_ray_origin(si.position, ng, reflected);
    next.dir = reflected;
    ray = next;
  }
}

// What a guide sample (one feature ray's, or a pixel's mean of them) shows of the surface.
struct SurfaceView {
  const Color& albedo;
  const Vec3f& normal;
  const Vec3f& position;
  bool sky;  // then the position is far along the ray, on no plane
};

// Whether two guide samples show the same surface, so that rays between them would most likely
// too: the same albedo and normal and, unless both see the sky, the same plane.
bool same_surface(const SurfaceView& a, const SurfaceView& b) {
  constexpr float kAlbedo = 1e-3f, kNormalCosine = 0.999f, kPlaneSine = 1e-3f;
  const Color d = a.albedo - b.albedo;
  if (std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}) > kAlbedo) return false;
  if (dot(a.normal, b.normal) < kNormalCosine) return false;
  if (a.sky || b.sky) return a.sky == b.sky;
  const Vec3f between = b.position - a.position;
  return std::abs(dot(between, a.normal)) <= kPlaneSine * length(between);
}

// Whether two feature rays of one pixel saw the same thing.
bool same_feature(const Feature& a, const Feature& b) {
  return a.emitter == b.emitter && a.lit_surface == b.lit_surface &&
         same_surface({a.albedo, a.normal, a.position, a.sky},
                      {b.albedo, b.normal, b.position, b.sky});
}

// A pixel's next-event samples for the visibility guide: each one's weight, its unshadowed
// irradiance estimate (luminance x cosine / pdf, so bright lights count for more, as in the
// image), and whether it reached its light.
struct VisibilitySums {
  static constexpr int kMost = [] {
    int most = 0;
    for (int side = 1; side <= kFeatureRaysPerSide; ++side)
      most = std::max(most, side * side * visibility_samples_per_ray(side));
    return most;
  }();
  std::array<float, kMost> weight{}, visible{};  // visible: 1, occluded: 0
  int count = 0;
  int lit_rays = 0;     // feature rays that ended on a surface that reflects light
  bool mixed() const {  // some samples reached their light and some did not
    for (int i = 1; i < count; ++i)
      if (visible[i] != visible[0]) return true;
    return false;
  }
};

// `samples` samples of the direct light at the surface a feature ray ended on.
void add_visibility(const LightSampler& lights, const Accel& accel, const Feature& at, int samples,
                    Pcg32& rng, VisibilitySums& sums) {
  ++sums.lit_rays;
  for (int k = 0; k < samples; ++k) {
    // Stratified light choice: the ray's samples spread over the selection's CDF.
    const float u_select = (k + rng.next_float()) / static_cast<float>(samples);
    const LightSample ls = lights.sample(at.position, {u_select, rng.next_float()});
    const float cosine = dot(ls.wi, at.normal);
    float weight = 0;
    if (ls.pdf > 0 && cosine > 0 && dot(ls.wi, at.geometric_normal) > 0)
      weight = luminance(ls.radiance) * cosine / ls.pdf;
    if (!(weight > 0) || !std::isfinite(weight)) continue;  // no light to block
    Ray shadow;
    shadow.org = offset_ray_origin(at.position, at.geometric_normal, ls.wi);
    shadow.dir = ls.wi;
    shadow.tfar = ls.distance < kInf ? ls.distance * (1.0f - 1e-4f) : kInf;
    sums.weight[sums.count] = weight;
    sums.visible[sums.count] = accel.occluded(shadow) ? 0.0f : 1.0f;
    ++sums.count;
  }
}

// The pixel's visibility: the surfaces' weighted share of visible samples (a ratio estimate)
// over the share of its feature rays that saw a surface, 1 over the rest.
void set_visibility(const VisibilitySums& sums, int rays, DenoiseFeatures& f, size_t p) {
  double total = 0, visible = 0;
  for (int i = 0; i < sums.count; ++i) {
    total += sums.weight[i];
    visible += sums.weight[i] * sums.visible[i];
  }
  const double share = total > 0 ? visible / total : 0.0;
  // The ratio estimate's variance to first order: sum of w^2 (v - share)^2 / (sum of w)^2.
  double spread = 0;
  for (int i = 0; i < sums.count; ++i) {
    const double d = sums.weight[i] * (sums.visible[i] - share);
    spread += d * d;
  }
  const double surfaces = static_cast<double>(sums.lit_rays) / rays;
  f.visibility[p] = static_cast<float>(surfaces * share + (1.0 - surfaces));
  f.visibility_variance[p] =
      total > 0 ? static_cast<float>(surfaces * surfaces * spread / (total * total)) : 0.0f;
}

// An edge that crosses a pixel between its rays and its border shows in none of its rays, but
// its neighbour across the edge sees the other side: pixels whose features differ from a
// neighbour's are marked as detail too.
// `sky`: 1 where all of the pixel's rays saw the sky (its positions are far along the rays, on no
// plane).
void mark_edges_between_pixels(DenoiseFeatures& f, const std::vector<uint8_t>& sky) {
  const int w = f.width, h = f.height;
  auto same = [&](size_t p, size_t q) {
    constexpr float kVisibility = 1e-3f;
    if (f.emitter[p] != f.emitter[q]) return false;
    if (!f.visibility.empty() && std::abs(f.visibility[p] - f.visibility[q]) > kVisibility)
      return false;
    return same_surface({f.albedo[p], f.normal[p], f.position[p], sky[p] != 0},
                        {f.albedo[q], f.normal[q], f.position[q], sky[q] != 0});
  };
  // `same` reads no detail flag, so each pixel's flag is set in place.
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y)
      for (int x = 0; x < w; ++x) {
        const size_t p = static_cast<size_t>(y) * w + x;
        if ((x + 1 < w && !same(p, p + 1)) || (x > 0 && !same(p, p - 1)) ||
            (y + 1 < h && !same(p, p + w)) || (y > 0 && !same(p, p - w)))
          f.detail[p] = 1;
      }
  });
}

}  // namespace

DenoiseFeatures render_denoise_features(const TileRenderer& renderer, int rays_per_side,
                                        const DenoiseFeatures* coarse) {
  if (rays_per_side < 1 || rays_per_side > kFeatureRaysPerSide)
    throw std::invalid_argument("denoiser features: " + std::to_string(rays_per_side) +
                                " rays per pixel side (1 to " +
                                std::to_string(kFeatureRaysPerSide) + ")");
  const RenderSettings& s = renderer.settings();
  const Scene& scene = renderer.scene();
  const Accel& accel = renderer.integrator().accel();
  const Camera& camera = renderer.camera();
  const size_t pixels = static_cast<size_t>(s.width) * s.height;
  const LightSampler& lights = renderer.integrator().lights();
  if (coarse &&
      (coarse->width != s.width || coarse->height != s.height || coarse->detail.size() != pixels ||
       coarse->visibility.size() != (lights.empty() ? 0 : pixels)))
    throw std::invalid_argument("denoiser features: the coarse features are of another view");
  DenoiseFeatures f;
  if (coarse) {
    f = *coarse;
  } else {
    f.width = s.width;
    f.height = s.height;
    f.albedo.assign(pixels, Color(0.0f));
    f.normal.assign(pixels, Vec3f(0.0f));
    f.emitter.assign(pixels, 0);
    f.position.assign(pixels, Vec3f(0.0f));
    f.detail.assign(pixels, 1);
    if (!lights.empty()) {
      f.visibility.assign(pixels, 1.0f);
      f.visibility_variance.assign(pixels, 0.0f);
    }
  }
  const float sky_distance = kSkyDistance * std::max(1.0f, scene.bounds().diagonal());
  const int side = rays_per_side;
  const float weight = 1.0f / static_cast<float>(side * side);
  const int light_samples = visibility_samples_per_ray(side);
  std::vector<uint8_t> sky(coarse ? 0 : pixels, 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, s.height), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y)
      for (int x = 0; x < s.width; ++x) {
        size_t p = static_cast<size_t>(y) * s.width + x;
        if (!f.detail[p]) continue;  // the coarse rays all agreed
        Color albedo(0.0f);
        Vec3f normal(0.0f), position(0.0f);
        bool emitter = false, detail = false;
        Feature first;
        // Seeded by the pixel: the guide is the same on every run and from every scheduler.
        Pcg32 rng(p, 0x9e3779b97f4a7c15ULL);
        VisibilitySums visibility;
        for (int j = 0; j < side; ++j)
          for (int i = 0; i < side; ++i) {
            Vec2f at{x + (i + 0.5f) / side, y + (j + 0.5f) / side};
            Feature one =
                trace_feature(scene, accel, camera.generate_ray(at, {0.5f, 0.5f}), sky_distance);
            if (i == 0 && j == 0)
              first = one;
            else
              detail = detail || !same_feature(first, one);
            albedo += one.albedo * weight;
            position += one.position * weight;
            normal += one.normal;
            emitter = emitter || one.emitter;
            if (one.lit_surface && !lights.empty())
              add_visibility(lights, accel, one, light_samples, rng, visibility);
          }
        if (!lights.empty()) set_visibility(visibility, side * side, f, p);
        f.albedo[p] = albedo;
        f.emitter[p] = emitter;
        f.position[p] = position;
        f.detail[p] = side == 1 || detail || visibility.mixed();  // one ray cannot tell
        if (!coarse) sky[p] = first.sky && !detail;
        float len = length(normal);
        // Opposite normals in one pixel (a thin sheet's edge) cancel: any unit vector will do.
        f.normal[p] = len > 1e-6f ? normal / len : Vec3f(0.0f, 0.0f, 1.0f);
      }
  });
  if (!coarse) mark_edges_between_pixels(f, sky);
  return f;
}

}  // namespace tuneray
