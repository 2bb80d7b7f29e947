#include "render/light_sampler.h"

#include <cmath>

#include "render/simd8_lookup.h"

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

  Planes& q = planes_;
  const size_t n = selection_.size();
  for (auto* v : {&q.px, &q.py, &q.pz, &q.e1x, &q.e1y, &q.e1z, &q.e2x, &q.e2y, &q.e2z, &q.nx, &q.ny,
                  &q.nz, &q.area, &q.rx, &q.ry, &q.rz, &q.pmf, &q.cdf, &q.cdf_width})
    v->assign(simd::lookup_table_size(n), 0.0f);  // padded for sample8's lookups
  q.two_sided.assign(simd::lookup_table_size(n), 0);
  for (size_t j = 0; j < n; ++j) {
    q.pmf[j] = selection_.pmf(j);
    q.cdf[j] = selection_.cdf(j);
    q.cdf_width[j] = selection_.cdf(j + 1) - selection_.cdf(j);
    Vec3f position, e1, e2, normal, radiance;
    if (j < emissive_.size()) {
      const EmissiveTriangle& et = emissive_[j];
      const Material& m = scene.materials[scene.material_ids[et.prim]];
      position = et.p0;
      e1 = et.edge1;
      e2 = et.edge2;
      normal = et.normal;
      radiance = material_emission(scene, et.prim);
      q.area[j] = et.area;
      q.two_sided[j] = m.two_sided_emission ? -1 : 0;
    } else if (j < env_index_) {
      const PointLight& pl = scene.point_lights[j - point_begin_];
      position = pl.position;
      radiance = pl.intensity * scene.light_scale;
    }
    q.px[j] = position.x, q.py[j] = position.y, q.pz[j] = position.z;
    q.e1x[j] = e1.x, q.e1y[j] = e1.y, q.e1z[j] = e1.z;
    q.e2x[j] = e2.x, q.e2y[j] = e2.y, q.e2z[j] = e2.z;
    q.nx[j] = normal.x, q.ny[j] = normal.y, q.nz[j] = normal.z;
    q.rx[j] = radiance.x, q.ry[j] = radiance.y, q.rz[j] = radiance.z;
  }
}

LightSample8 LightSampler::sample8(const simd::V8& p, simd::F8 u0, simd::F8 u1,
                                   uint32_t lanes) const {
  using simd::F8;
  using simd::I8;
  using simd::M8;
  using simd::V8;
  LightSample8 ls;
  ls.pdf = F8(0.0f);
  ls.distance = F8(0.0f);
  ls.wi = V8(F8(0.0f));
  ls.radiance = V8(F8(0.0f));
  ls.is_delta = M8::none();
  ls.u_in_light = u0;
  if (empty() || !lanes) return ls;

  // The bin: sample_discrete's count of the bins starting at or below u, or its search.
  const F8 u_select = u0;
  const size_t n = selection_.size();
  I8 index(0);
  if (n <= Distribution1D::kLinearSearchBins) {
    for (size_t j = 1; j < n; ++j) {
      const M8 at_or_below = F8(planes_.cdf[j]) <= u_select;
      index = index + I8(_mm256_srli_epi32(_mm256_castps_si256(at_or_below.v), 31));
    }
  } else {
    alignas(32) int32_t bins[simd::kLanes] = {};
    alignas(32) float u[simd::kLanes];
    u_select.store(u);
    for (uint32_t m = lanes; m; m &= m - 1) {
      const int i = __builtin_ctz(m);
      bins[i] = static_cast<int32_t>(selection_.sample_discrete(u[i], nullptr));
    }
    index = I8::load(bins);
  }
  // Lanes outside `lanes` read bin 0, which exists; their results are discarded.
  index = simd::select(M8::from_bits(lanes), index, I8(0));
  const auto at_bin = [&](const std::vector<float>& plane) {
    return simd::lookup(plane, n, index);
  };
  const F8 pmf = at_bin(planes_.pmf);
  M8 ok = M8::from_bits(lanes) & (pmf > F8(0.0f));
  {
    // sample_discrete's u_remapped: the selecting number again, rescaled inside its bin.
    const F8 width = at_bin(planes_.cdf_width);
    const F8 r = (u_select - at_bin(planes_.cdf)) / simd::select(width > F8(0.0f), width, F8(1.0f));
    u0 = simd::min(simd::max(simd::keep(width > F8(0.0f), r), F8(0.0f)), F8(kOneMinusEpsilon));
    ls.u_in_light = u0;
  }

  const M8 is_env =
      ok & (index == I8(static_cast<int32_t>(env_index_ == SIZE_MAX ? -1 : env_index_)));
  const M8 is_point = ok.and_not(is_env) & (index >= I8(static_cast<int32_t>(point_begin_)));
  const M8 is_triangle = ok.and_not(is_env | is_point);

  const V8 position(at_bin(planes_.px), at_bin(planes_.py), at_bin(planes_.pz));
  const V8 radiance(at_bin(planes_.rx), at_bin(planes_.ry), at_bin(planes_.rz));
  V8 target = position;
  if (is_triangle.any()) {
    // sample_uniform_triangle, then the point on the triangle.
    const M8 upper = u1 > u0;
    const F8 b0 = simd::select(upper, 0.5f * u0, u0 - 0.5f * u1);
    const F8 b1 = simd::select(upper, u1 - 0.5f * u0, 0.5f * u1);
    const F8 bx = b1, by = 1.0f - b0 - b1;
    const V8 e1(at_bin(planes_.e1x), at_bin(planes_.e1y), at_bin(planes_.e1z));
    const V8 e2(at_bin(planes_.e2x), at_bin(planes_.e2y), at_bin(planes_.e2z));
    target = simd::select(is_triangle, position + e1 * bx + e2 * by, position);
  }
  const V8 d = target - p;
  const F8 dist2 = dot(d, d);
  ok &= dist2 > F8(0.0f);
  const F8 distance = sqrt(dist2);
  const V8 wi = d * (1.0f / distance);
  const M8 points = is_point & ok;
  ls.wi = keep(points, wi);
  ls.distance = keep(points, distance);
  ls.radiance = keep(points, radiance * (1.0f / dist2));
  ls.pdf = keep(points, pmf);
  ls.is_delta = points;

  const M8 triangles = is_triangle & ok;
  if (triangles.any()) {
    const V8 normal(at_bin(planes_.nx), at_bin(planes_.ny), at_bin(planes_.nz));
    const F8 cos_signed = dot(normal, wi);
    const F8 cos_light = simd::abs(cos_signed);
    const M8 lit = triangles & (cos_light > F8(1e-7f));
    // emitted(): one-sided emitters light only the side their normal faces (dot(n, -wi) > 0).
    const M8 two_sided(_mm256_castsi256_ps(simd::lookup(planes_.two_sided, n, index).v));
    const M8 facing = two_sided | (dot(normal, -wi) > F8(0.0f));
    const F8 area = at_bin(planes_.area);
    ls.wi = simd::select(lit, wi, ls.wi);
    ls.distance = simd::select(lit, distance, ls.distance);
    ls.radiance = simd::select(lit, keep(facing, radiance), ls.radiance);
    ls.pdf = simd::select(lit, pmf * dist2 / (cos_light * area), ls.pdf);
  }

  if (is_env.any() && environment_.is_constant()) {
    // sample_uniform_sphere, 8 wide.
    const F8 z = 1.0f - 2.0f * u0;
    const F8 r = sqrt(simd::max(F8(0.0f), 1.0f - z * z));
    F8 sin_phi, cos_phi;
    simd::sincos_turn(u1, sin_phi, cos_phi);
    const Color c = environment_.constant();
    ls.wi = simd::select(is_env, V8(r * cos_phi, r * sin_phi, z), ls.wi);
    ls.radiance = simd::select(is_env, V8(F8(c.x), F8(c.y), F8(c.z)), ls.radiance);
    ls.pdf = simd::select(is_env, kUniformSpherePdf * pmf, ls.pdf);
    ls.distance = simd::select(is_env, F8(kInf), ls.distance);
  } else if (is_env.any()) {
    alignas(32) float ua[simd::kLanes], ub[simd::kLanes], pm[simd::kLanes];
    u0.store(ua);
    u1.store(ub);
    pmf.store(pm);
    alignas(32) float wx[8], wy[8], wz[8], rx[8], ry[8], rz[8], pdf[8];
    ls.wi.x.store(wx), ls.wi.y.store(wy), ls.wi.z.store(wz);
    ls.radiance.x.store(rx), ls.radiance.y.store(ry), ls.radiance.z.store(rz);
    ls.pdf.store(pdf);
    for (uint32_t m = is_env.bits(); m; m &= m - 1) {
      const int i = __builtin_ctz(m);
      EnvironmentSample es = environment_.sample({ua[i], ub[i]});
      wx[i] = es.wi.x, wy[i] = es.wi.y, wz[i] = es.wi.z;
      rx[i] = es.radiance.x, ry[i] = es.radiance.y, rz[i] = es.radiance.z;
      pdf[i] = es.pdf * pm[i];
    }
    ls.wi = V8(F8::load(wx), F8::load(wy), F8::load(wz));
    ls.radiance = V8(F8::load(rx), F8::load(ry), F8::load(rz));
    ls.pdf = F8::load(pdf);
    ls.distance = simd::select(is_env, F8(kInf), ls.distance);
  }
  return ls;
}

LightSample LightSampler::sample(Vec3f p, Vec2f u) const {
  LightSample ls;
  if (empty()) return ls;
  float pmf = 0;
  size_t index = selection_.sample_discrete(u.x, &pmf, &u.x);
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

Color LightSampler::emitted(uint32_t prim, Vec3f geometric_normal, Vec3f wo) const {
  const Material& m = scene_.materials[scene_.material_ids[prim]];
  if (!m.two_sided_emission && dot(geometric_normal, wo) <= 0) return Color(0.0f);
  return m.emission * scene_.light_scale;
}

}  // namespace tuneray
