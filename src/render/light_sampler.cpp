#include "render/light_sampler.h"

#include <cmath>

namespace tuneray {

namespace {
Color material_emission(const Scene& scene, uint32_t prim) {
  return scene.materials[scene.material_ids[prim]].emission * scene.light_scale;
}
}  // namespace

LightSampler::LightSampler(const Scene& scene, const EnvironmentLight& environment)
    : scene_(scene), environment_(environment) {
  std::vector<float> weights;
  emissive_index_of_prim_.assign(scene.triangles.size(), -1);
  for (uint32_t i = 0; i < scene.triangles.size(); ++i) {
    const Material& m = scene.materials[scene.material_ids[i]];
    if (!m.is_emissive()) continue;
    const Triangle& t = scene.triangles[i];
    Vec3f p0 = scene.positions[t.v[0]], p1 = scene.positions[t.v[1]], p2 = scene.positions[t.v[2]];
    Vec3f ng = cross(p1 - p0, p2 - p0);
    float area = 0.5f * length(ng);
    if (!(area > 0)) continue;
    emissive_index_of_prim_[i] = static_cast<int32_t>(emissive_.size());
    emissive_.push_back({i, area, p0, p1 - p0, p2 - p0, ng / (2.0f * area)});
    float sides = m.two_sided_emission ? 2.0f : 1.0f;
    weights.push_back(luminance(material_emission(scene, i)) * area * kPi * sides);
  }
  point_begin_ = weights.size();
  for (const PointLight& pl : scene.point_lights)
    weights.push_back(4.0f * kPi * luminance(pl.intensity) * scene.light_scale);
  if (environment.active()) {
    // An environment's power reaching the scene: radiance x pi x (bounding-sphere radius)^2.
    float radius = 0.5f * scene.bounds().diagonal();
    float env_weight = environment.mean_luminance() * kPi * kPi * radius * radius;
    if (weights.empty() || !(env_weight > 0)) env_weight = 1.0f;
    env_index_ = weights.size();
    weights.push_back(env_weight);
  }
  if (!weights.empty()) selection_ = Distribution1D(weights);
}

LightSample LightSampler::sample(Vec3f p, float u_select, Vec2f u) const {
  LightSample ls;
  if (empty()) return ls;
  float pmf = 0;
  size_t index = selection_.sample_discrete(u_select, &pmf);
  if (!(pmf > 0)) return ls;
  if (index == env_index_) {
    EnvironmentSample es = environment_.sample(u);
    ls.wi = es.wi;
    ls.distance = kInf;
    ls.radiance = es.radiance;
    ls.pdf = es.pdf * pmf;
    return ls;
  }
  if (index >= point_begin_) {
    const PointLight& pl = scene_.point_lights[index - point_begin_];
    Vec3f d = pl.position - p;
    float dist2 = dot(d, d);
    if (!(dist2 > 0)) return ls;
    ls.distance = std::sqrt(dist2);
    ls.wi = d / ls.distance;
    ls.radiance = pl.intensity * scene_.light_scale / dist2;
    ls.pdf = pmf;
    ls.is_delta = true;
    return ls;
  }
  const EmissiveTriangle& et = emissive_[index];
  Vec2f b = sample_uniform_triangle(u);
  Vec3f q = et.p0 + et.edge1 * b.x + et.edge2 * b.y;
  const Vec3f& n = et.normal;
  Vec3f d = q - p;
  float dist2 = dot(d, d);
  if (!(dist2 > 0)) return ls;
  ls.distance = std::sqrt(dist2);
  ls.wi = d / ls.distance;
  float cos_light = std::abs(dot(n, ls.wi));
  if (!(cos_light > 1e-7f)) return ls;
  ls.radiance = emitted(et.prim, n, -ls.wi);
  ls.pdf = pmf * dist2 / (cos_light * et.area);
  return ls;
}

float LightSampler::pdf_triangle(uint32_t prim, Vec3f p, Vec3f light_point,
                                 Vec3f light_normal) const {
  int32_t index = emissive_index_of_prim_[prim];
  if (index < 0) return 0.0f;
  Vec3f d = light_point - p;
  float dist2 = dot(d, d);
  float cos_light = std::abs(dot(light_normal, d)) / std::sqrt(dist2);
  if (!(cos_light > 1e-7f)) return 0.0f;
  return selection_.pmf(static_cast<size_t>(index)) * dist2 /
         (cos_light * emissive_[static_cast<size_t>(index)].area);
}

float LightSampler::pdf_environment(Vec3f dir) const {
  if (env_index_ == SIZE_MAX) return 0.0f;
  return selection_.pmf(env_index_) * environment_.pdf(dir);
}

Color LightSampler::emitted(uint32_t prim, Vec3f geometric_normal, Vec3f wo) const {
  const Material& m = scene_.materials[scene_.material_ids[prim]];
  if (!m.two_sided_emission && dot(geometric_normal, wo) <= 0) return Color(0.0f);
  return m.emission * scene_.light_scale;
}

}  // namespace tuneray
