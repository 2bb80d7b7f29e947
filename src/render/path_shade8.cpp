// PathIntegrator::shade8: the shading step of up to eight paths at once. The math that every
// bounce does (hit point and frames, the material and its regularization, light sampling, BSDF
// evaluation and sampling, MIS, Russian roulette, the next ray, misses under a constant
// environment) runs in AVX2 lanes; what is rare or table-driven (misses under an environment map,
// emitters hit, texture lookups, the dielectric) runs per lane with the scalar code. Every step
// is lane by lane, so a path's result does not depend on its neighbours.
#include <algorithm>
#include <cmath>

#include "render/bsdf8.h"
#include "render/path_integrator.h"
#include "render/simd8_lookup.h"
#include "render/surface.h"

namespace tuneray {

using simd::F8;
using simd::kLanes;
using simd::M8;
using simd::V8;

namespace {

// Eight scalars written lane by lane, read as one register.
struct LaneFloats {
  alignas(32) float v[kLanes];
  LaneFloats() { _mm256_store_ps(v, _mm256_setzero_ps()); }
  F8 get() const { return F8::load(v); }
};
struct LaneVecs {
  LaneFloats x, y, z;
  void set(int i, Vec3f p) {
    x.v[i] = p.x;
    y.v[i] = p.y;
    z.v[i] = p.z;
  }
  V8 get() const { return {x.get(), y.get(), z.get()}; }
};
// Eight rows of three floats (x, y, z), one per lane, read as planes: each row by one masked
// 128-bit load, then a transpose. Writing the floats lane by lane and reading them as a vector
// stalls on store forwarding. Lanes never set read a row of zeros.
struct LaneRows {
  alignas(16) static constexpr float kZeroRow[4] = {};
  const float* at[kLanes] = {kZeroRow, kZeroRow, kZeroRow, kZeroRow,
                             kZeroRow, kZeroRow, kZeroRow, kZeroRow};
  void set(int i, const Vec3f& row) { at[i] = &row.x; }
  V8 get() const {
    static_assert(sizeof(Vec3f) == 3 * sizeof(float));
    const __m128i xyz = _mm_setr_epi32(-1, -1, -1, 0);  // the fourth float may lie past an array
    const auto pair = [&](int lo) {
      return _mm256_set_m128(_mm_maskload_ps(at[lo + 4], xyz), _mm_maskload_ps(at[lo], xyz));
    };
    const __m256 r0 = pair(0), r1 = pair(1), r2 = pair(2), r3 = pair(3);
    const __m256 xy01 = _mm256_unpacklo_ps(r0, r1), z01 = _mm256_unpackhi_ps(r0, r1);
    const __m256 xy23 = _mm256_unpacklo_ps(r2, r3), z23 = _mm256_unpackhi_ps(r2, r3);
    return {F8(_mm256_shuffle_ps(xy01, xy23, 0x44)), F8(_mm256_shuffle_ps(xy01, xy23, 0xEE)),
            F8(_mm256_shuffle_ps(z01, z23, 0x44))};
  }
};
struct LaneOut {
  alignas(32) float x[kLanes], y[kLanes], z[kLanes];
  explicit LaneOut(const V8& v) {
    v.x.store(x);
    v.y.store(y);
    v.z.store(z);
  }
  Vec3f operator[](int i) const { return {x[i], y[i], z[i]}; }
};
struct LaneScalars {
  alignas(32) float v[kLanes];
  explicit LaneScalars(F8 f) { f.store(v); }
  float operator[](int i) const { return v[i]; }
};

struct Frame8 {
  V8 s, t, n;
  V8 to_local(const V8& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  V8 to_world(const V8& v) const { return s * v.x + t * v.y + n * v.z; }
};

// Frame::from_normal (Duff et al. 2017).
Frame8 frame_from_normal(const V8& n) {
  const F8 sign = simd::copysign(F8(1.0f), n.z);
  const F8 a = -1.0f / (sign + n.z);
  const F8 b = n.x * n.y * a;
  return {V8(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), V8(b, sign + n.y * n.y * a, -n.y),
          n};
}

// Frame::from_normal_tangent.
Frame8 frame_from_normal_tangent(const V8& n, const V8& tangent) {
  V8 s = tangent - n * dot(n, tangent);
  const F8 len = length(s);
  const M8 ok = len > F8(1e-6f);
  s = s / simd::select(ok, len, F8(1.0f));
  Frame8 f{s, cross(n, s), n};
  if ((!ok).any()) {
    const Frame8 g = frame_from_normal(n);
    f.s = simd::select(ok, f.s, g.s);
    f.t = simd::select(ok, f.t, g.t);
  }
  return f;
}

// offset_ray_origin.
V8 offset_ray_origin(const V8& p, const V8& n, const V8& dir) {
  const F8 magnitude = simd::max(simd::max(simd::abs(p.x), simd::abs(p.y)), simd::abs(p.z));
  const F8 eps = 1e-4f * simd::max(F8(1.0f), magnitude) * 0.05f;
  return p + n * simd::select(dot(n, dir) >= F8(0.0f), eps, -eps);
}

F8 power_heuristic(F8 a, F8 b) {
  const F8 a2 = a * a, b2 = b * b;
  return simd::select(a2 + b2 > F8(0.0f), a2 / (a2 + b2), F8(0.0f));
}

// Path reuse (path_reuse.h): what the pool pass needs of the lanes at their first or second hit.
// `lambert` the lanes that scatter on a Lambertian surface, `below` those whose shading frame
// was replaced by the geometric one, `sampled` those with a next direction; the normals face
// the incoming ray; `throughput` is the throughput into the next vertex (before roulette,
// which reuse_pool_pixels keeps away from the first hit).
void record_reuse(PathWave& w, size_t begin, M8 lambert, M8 below, M8 sampled, const V8& position,
                  const V8& normal, const V8& shading_normal, const V8& throughput) {
  const simd::I8 depth = simd::I8::load(w.depth.data() + begin);
  const M8 first = lambert & (depth == simd::I8(0));
  const M8 second = lambert.and_not(below) & (depth == simd::I8(1));
  if (!(first | second).any()) return;
  const M8 technique = first & sampled & (throughput.x > F8(0.0f)) & (throughput.y > F8(0.0f)) &
                       (throughput.z > F8(0.0f));
  const LaneOut at(position), ng(normal), ns(shading_normal), w1(throughput);
  for (uint32_t m = (first | second).bits(); m; m &= m - 1) {
    const int i = __builtin_ctz(m);
    const size_t k = begin + static_cast<size_t>(i);
    ReuseVertices& r = w.reuse[w.slot[k]];
    if ((first.bits() >> i) & 1) {
      r.technique = (technique.bits() >> i) & 1;
      r.p1 = at[i], r.n1 = ns[i], r.ng1 = ng[i], r.w1 = w1[i];
    } else if (r.technique) {
      r.shared = true;
      r.p2 = at[i], r.ng2 = ng[i], r.ns2 = ns[i], r.l2 = w.radiance(k);
    }
  }
}

}  // namespace

void PathIntegrator::shade_misses(PathWave& w, size_t begin, M8 missed) const {
  // shade_miss for a constant environment, 8 wide: its radiance is one colour; its light
  // samples' pdf is uniform, or the BSDF's own (the previous vertex's, times the selection).
  const simd::I8 flags = simd::I8::load(w.flags.data() + begin);
  auto flag = [&flags](int32_t bit) {
    return M8(_mm256_castsi256_ps(_mm256_cmpeq_epi32(
        _mm256_and_si256(flags.v, _mm256_set1_epi32(bit)), _mm256_set1_epi32(bit))));
  };
  const M8 previous_delta = flag(PathWave::kPreviousWasDelta);
  const M8 specular_chain = flag(PathWave::kSpecularChain);
  F8 weight(1.0f);
  if (settings_.strategy == LightStrategy::kLightOnly) {
    weight = simd::keep(previous_delta, weight);
  } else if (settings_.strategy == LightStrategy::kMis) {
    const F8 previous_pdf = F8::load(w.plane(PathWave::kPrevPdf) + begin);
    const float pmf = lights_.environment_pmf();
    const F8 env_pdf =
        settings_.quality.bsdf_sky ? previous_pdf * pmf : F8(pmf * kUniformSpherePdf);
    weight = simd::select(previous_delta, weight, power_heuristic(previous_pdf, env_pdf));
  }
  const Color c = environment_.constant();
  const V8 beta(F8::load(w.plane(PathWave::kBetaX) + begin),
                F8::load(w.plane(PathWave::kBetaY) + begin),
                F8::load(w.plane(PathWave::kBetaZ) + begin));
  const V8 seen = beta * V8(F8(c.x), F8(c.y), F8(c.z)) * weight;
  const M8 to_camera = missed & specular_chain, to_rest = missed.and_not(specular_chain);
  for (int k = 0; k < 3; ++k) {
    const F8 v = k == 0 ? seen.x : (k == 1 ? seen.y : seen.z);
    float* camera = w.plane(PathWave::kCameraX + k) + begin;
    float* rest = w.plane(PathWave::kLX + k) + begin;
    (F8::load(camera) + simd::keep(to_camera, v)).store(camera);
    (F8::load(rest) + simd::keep(to_rest, v)).store(rest);
  }
}

uint32_t PathIntegrator::shade8(PathWave& w, size_t begin, int count, const Hit* hits,
                                const float* const* u, ShadowRequest* shadow) const {
  const bool use_nee = settings_.strategy != LightStrategy::kBsdfOnly;
  const bool mis = settings_.strategy == LightStrategy::kMis;
  auto load = [&](int plane) { return F8::load(w.plane(plane) + begin); };
  auto load3 = [&](int plane) { return V8(load(plane), load(plane + 1), load(plane + 2)); };
  auto store = [&](int plane, F8 v) { v.store(w.plane(plane) + begin); };
  auto store3 = [&](int plane, const V8& v) {
    store(plane, v.x);
    store(plane + 1, v.y);
    store(plane + 2, v.z);
  };

  // --- Per lane: misses, emission, the end of the path; gathering for the lanes that scatter.
  uint32_t scatter = 0;
  LaneRows p0, p1, p2, n0, n1, n2, ng, flat_normal, flat_tangent;
  LaneFloats bu, bv;
  alignas(32) int32_t material_of[kLanes] = {};
  uint32_t flat = 0, textured = 0, missed = 0;
  for (int i = 0; i < count; ++i) {
    const size_t k = begin + static_cast<size_t>(i);
    shadow[i].active = false;
    // A path training the cache: its tail is what it adds from here on (before this vertex's
    // emission, after the cached vertex's light sample).
    if (cache_ && w.depth[k] == settings_.quality.cache.vertex + 1 && w.cache_key(k) != 0)
      w.snapshot_for_cache(k);
    const Hit& hit = hits[i];
    if (!hit.valid()) {
      missed |= 1u << i;
      if (environment_.active() && !environment_.is_constant()) shade_miss(w, k);
      continue;
    }
    const TriangleShading& ts = geometry_.triangle(hit.prim);
    const MaterialPlanes& mp = material_planes_;
    if (mp.emissive[ts.material]) add_emission(w, k, hit);
    if (w.depth[k] >= settings_.max_bounces) continue;
    scatter |= 1u << i;
    material_of[i] = static_cast<int32_t>(ts.material);
    const Triangle& tri = scene_.triangles[hit.prim];
    p0.set(i, scene_.positions[tri.v[0]]);
    p1.set(i, scene_.positions[tri.v[1]]);
    p2.set(i, scene_.positions[tri.v[2]]);
    bu.v[i] = hit.u;
    bv.v[i] = hit.v;
    ng.set(i, ts.geometric_normal);
    if (ts.flat) {
      flat |= 1u << i;
      flat_normal.set(i, ts.normal);
      flat_tangent.set(i, ts.tangent);
    } else {
      n0.set(i, scene_.normals[tri.v[0]]);
      n1.set(i, scene_.normals[tri.v[1]]);
      n2.set(i, scene_.normals[tri.v[2]]);
    }
    if (mp.textured[ts.material]) textured |= 1u << i;
  }
  if (missed && environment_.is_constant()) shade_misses(w, begin, M8::from_bits(missed));
  if (!scatter) return 0;

  // --- The hit point and its frames (ShadingGeometry::interaction), 8 wide.
  const M8 lanes = M8::from_bits(scatter);
  const F8 u_bary = bu.get(), v_bary = bv.get(), w0 = 1.0f - u_bary - v_bary;
  const V8 a = p0.get(), c = p1.get(), d = p2.get();
  const V8 position = a * w0 + c * u_bary + d * v_bary;
  V8 normal = ng.get();
  Frame8 shading;
  const M8 is_flat = M8::from_bits(flat);
  if (flat) {
    const V8 fn = flat_normal.get(), ft = flat_tangent.get();
    shading = {ft, cross(fn, ft), fn};
  }
  if (scatter & ~flat) {
    V8 ns = n0.get() * w0 + n1.get() * u_bary + n2.get() * v_bary;
    const F8 ns_len = length(ns);
    const M8 ok = (ns_len > F8(0.0f)) & simd::is_finite(ns_len);
    ns = simd::select(ok, ns / simd::select(ok, ns_len, F8(1.0f)), normal);
    const Frame8 smooth = frame_from_normal_tangent(ns, c - a);
    shading.s = simd::select(is_flat, shading.s, smooth.s);
    shading.t = simd::select(is_flat, shading.t, smooth.t);
    shading.n = simd::select(is_flat, shading.n, smooth.n);
  }

  // --- The material at each hit (resolve_bsdf), regularized (regularize), 8 wide.
  const simd::I8 material = simd::I8::load(material_of);
  const MaterialPlanes& mp = material_planes_;
  const size_t materials = scene_.materials.size();
  auto per_material = [&](const std::vector<float>& plane) {
    return simd::lookup(plane, materials, material);
  };
  const simd::I8 type = simd::lookup(mp.type, materials, material);
  V8 base(per_material(mp.base_r), per_material(mp.base_g), per_material(mp.base_b));
  if (textured) {
    // resolve_bsdf's lookup: at the interpolated UV, or (0, 0) on a mesh without UVs.
    const LaneOut base_out(base);
    LaneVecs textured_base;
    for (int i = 0; i < kLanes; ++i) {
      if (!((textured >> i) & 1)) {
        textured_base.set(i, base_out[i]);
        continue;
      }
      const Hit& hit = hits[i];
      const Triangle& tri = scene_.triangles[hit.prim];
      Vec2f uv;
      if (!scene_.uvs.empty()) {
        const float b0 = 1.0f - hit.u - hit.v;
        uv =
            scene_.uvs[tri.v[0]] * b0 + scene_.uvs[tri.v[1]] * hit.u + scene_.uvs[tri.v[2]] * hit.v;
      }
      const Material& m = scene_.materials[static_cast<size_t>(material_of[i])];
      textured_base.set(i, base_out[i] * texture_factor(scene_, m, uv));
    }
    base = textured_base.get();
  }
  M8 is_lambert = lanes & (type == simd::I8(static_cast<int32_t>(MaterialType::kLambert)));
  M8 is_glossy = lanes & (type == simd::I8(static_cast<int32_t>(MaterialType::kGlossy)));
  const M8 is_principled =
      lanes & (type == simd::I8(static_cast<int32_t>(MaterialType::kPrincipled)));
  M8 is_mirror = lanes & (type == simd::I8(static_cast<int32_t>(MaterialType::kMirror)));
  const M8 is_dielectric =
      lanes & (type == simd::I8(static_cast<int32_t>(MaterialType::kDielectric)));
  F8 alpha_x = per_material(mp.alpha_x), alpha_y = per_material(mp.alpha_y);
  if (settings_.quality.regularize) {
    // regularize(): a lobe no sharper than the roughest vertex before it; Lambert counts as
    // roughness 1, a mirror behind a rough vertex turns into a GGX conductor of that roughness.
    F8 max_roughness = load(PathWave::kMaxRoughness);
    const M8 ggx = is_glossy | is_principled;
    const M8 widened_mirror = is_mirror & (max_roughness > F8(0.0f));
    alpha_x = simd::select(ggx, simd::max(alpha_x, max_roughness), alpha_x);
    alpha_y = simd::select(ggx, simd::max(alpha_y, max_roughness), alpha_y);
    alpha_x = simd::select(widened_mirror, max_roughness, alpha_x);
    alpha_y = simd::select(widened_mirror, max_roughness, alpha_y);
    F8 own = simd::keep(is_lambert, F8(1.0f));
    own = simd::select(ggx, simd::max(alpha_x, alpha_y), own);
    own = simd::select(widened_mirror, max_roughness, own);
    is_glossy |= widened_mirror;
    is_mirror = is_mirror.and_not(widened_mirror);
    store(PathWave::kMaxRoughness,
          simd::select(lanes, simd::max(max_roughness, own), max_roughness));
  }
  const M8 opaque = lanes.and_not(is_dielectric);
  const M8 smooth = is_lambert | is_glossy | is_principled;
  simd::SmoothBsdf8 bsdf;
  bsdf.lambert = is_lambert;
  bsdf.glossy = is_glossy;
  bsdf.principled = is_principled;
  bsdf.base = base;
  bsdf.specular =
      V8(per_material(mp.specular_r), per_material(mp.specular_g), per_material(mp.specular_b));
  // bsdf.cpp's clamp_alpha: anything not above the minimum (a NaN too) becomes the minimum.
  const F8 min_alpha(simd::kMinAlpha8);
  bsdf.ax = simd::select(alpha_x > min_alpha, alpha_x, min_alpha);
  bsdf.ay = simd::select(alpha_y > min_alpha, alpha_y, min_alpha);

  // facing_frame: opaque BSDFs see the side of the surface that wo is on.
  const V8 wo_world = -load3(PathWave::kDirX);
  const M8 flip = opaque & (dot(normal, wo_world) < F8(0.0f));
  normal = simd::select(flip, -normal, normal);
  shading.t = simd::select(flip, -shading.t, shading.t);
  shading.n = simd::select(flip, -shading.n, shading.n);
  const M8 below = opaque & (dot(shading.n, wo_world) <= F8(1e-6f));
  if (below.any()) {
    const Frame8 g = frame_from_normal_tangent(normal, shading.s);
    shading.s = simd::select(below, g.s, shading.s);
    shading.t = simd::select(below, g.t, shading.t);
    shading.n = simd::select(below, g.n, shading.n);
  }
  const V8 wo = shading.to_local(wo_world);
  auto load_u = [&](int k) { return F8::load(u[k] + begin); };

  // --- Next-event estimation, 8 wide (the environment's samples lane by lane).
  const V8 beta = load3(PathWave::kBetaX);
  uint32_t nee = use_nee && !lights_.empty() ? (smooth & lanes).bits() : 0;
  if (nee) {
    LightSample8 ls = lights_.sample8(position, load_u(kLightX), load_u(kLightY), nee);
    if (settings_.quality.bsdf_sky && environment_.is_constant()) {
      // The sky's samples follow the BSDF instead: its radiance is one colour, so the product
      // that NEE estimates is the BSDF's lobe times visibility, and no direction is wasted below
      // the surface. Their pdf is the selection's times the BSDF's.
      const M8 sky = M8::from_bits(nee) & (ls.distance >= F8(kInf)) & (ls.pdf > F8(0.0f));
      if (sky.any()) {
        const simd::BsdfSample8 shaped =
            simd::sample(bsdf, wo, load_u(kSkyLobe), ls.u_in_light, load_u(kLightY));
        ls.wi = simd::select(sky, shading.to_world(shaped.wi), ls.wi);
        ls.pdf = simd::select(sky, simd::keep(shaped.ok, shaped.pdf * lights_.environment_pmf()),
                              ls.pdf);
      }
    }
    if (settings_.quality.lowres_sky) {
      const M8 sky = M8::from_bits(nee) & (ls.distance >= F8(kInf)) & (ls.pdf > F8(0.0f));
      if (sky.any()) {
        const LaneOut dir(ls.wi);
        LaneVecs radiance;
        const LaneOut old(ls.radiance);
        for (int i = 0; i < kLanes; ++i)
          radiance.set(i, (sky.bits() >> i) & 1 ? environment_.eval_lowres(dir[i]) : old[i]);
        ls.radiance = radiance.get();
      }
    }
    const M8 usable = M8::from_bits(nee) & (ls.pdf > F8(0.0f)) &
                      (simd::max_component(ls.radiance) > F8(0.0f)) &
                      !(opaque & !(dot(ls.wi, normal) > F8(0.0f)));
    nee = usable.bits();
    if (nee) {
      const V8 wi = shading.to_local(ls.wi);
      simd::BsdfEval8 e;
      if (settings_.quality.branchless_materials) {
        // The branch-reduced formula (technique 4) stays the scalar one, lane by lane.
        const LaneOut wo_out(wo), wi_out(wi), base_out(bsdf.base), spec_out(bsdf.specular);
        const LaneScalars ax_out(alpha_x), ay_out(alpha_y);
        LaneVecs f;
        LaneFloats pdf;
        for (uint32_t m = nee; m; m &= m - 1) {
          const int i = __builtin_ctz(m);
          BsdfParams p = material_bsdf_[static_cast<size_t>(material_of[i])];
          p.type = (bsdf.glossy.bits() >> i) & 1 ? MaterialType::kGlossy : p.type;
          p.base_color = base_out[i];
          p.alpha_x = ax_out[i];
          p.alpha_y = ay_out[i];
          const BsdfEval s = bsdf_evaluate(p, wo_out[i], wi_out[i]);
          f.set(i, s.f);
          pdf.v[i] = s.pdf;
        }
        e.f = f.get();
        e.pdf = pdf.get();
      } else {
        e = simd::evaluate(bsdf, wo, wi);
      }
      const M8 lit = M8::from_bits(nee) & (simd::max_component(e.f) > F8(0.0f));
      if (lit.any()) {
        const V8 org = offset_ray_origin(position, normal, ls.wi);
        const F8 tfar =
            simd::select(ls.distance < F8(kInf), ls.distance * (1.0f - 1e-4f), F8(kInf));
        F8 weight(1.0f);
        if (mis) weight = simd::select(ls.is_delta, weight, power_heuristic(ls.pdf, e.pdf));
        const V8 contribution = beta * e.f * ls.radiance * (simd::abs(wi.z) * weight / ls.pdf);
        const LaneOut org_out(org), dir_out(ls.wi), contribution_out(contribution);
        const LaneScalars tfar_out(tfar);
        for (uint32_t m = lit.bits(); m; m &= m - 1) {
          const int i = __builtin_ctz(m);
          ShadowRequest& sr = shadow[i];
          sr.ray.org = org_out[i];
          sr.ray.tnear = 0.0f;
          sr.ray.dir = dir_out[i];
          sr.ray.tfar = tfar_out[i];
          sr.contribution = contribution_out[i];
          sr.active = true;
        }
      }
    }
  }

  // --- The next direction: smooth lobes 8 wide, the delta lobes per lane.
  const F8 u_lobe = load_u(kLobe), u_roulette = load_u(kRoulette);
  simd::BsdfSample8 bs = simd::sample(bsdf, wo, u_lobe, load_u(kBsdfX), load_u(kBsdfY));
  M8 delta = M8::none();
  if (is_mirror.any()) {
    const M8 ok = is_mirror & (wo.z > F8(0.0f));
    bs.wi = simd::select(is_mirror, V8(-wo.x, -wo.y, wo.z), bs.wi);
    bs.weight = simd::select(is_mirror, bsdf.specular, bs.weight);
    bs.pdf = simd::select(is_mirror, F8(1.0f), bs.pdf);
    bs.ok = simd::select(is_mirror, ok, bs.ok);
    delta |= is_mirror;
  }
  if (is_dielectric.any()) {
    const LaneOut wo_out(wo);
    const LaneScalars ul(u_lobe), u0(load_u(kBsdfX)), u1(load_u(kBsdfY));
    LaneVecs wi, weight;
    LaneFloats pdf;
    uint32_t ok = 0;
    for (uint32_t m = is_dielectric.bits(); m; m &= m - 1) {
      const int i = __builtin_ctz(m);
      BsdfSample s;
      if (bsdf_sample(material_bsdf_[static_cast<size_t>(material_of[i])], wo_out[i], ul[i],
                      {u0[i], u1[i]}, s))
        ok |= 1u << i;
      wi.set(i, s.wi);
      weight.set(i, s.weight);
      pdf.v[i] = s.pdf;
    }
    bs.wi = simd::select(is_dielectric, wi.get(), bs.wi);
    bs.weight = simd::select(is_dielectric, weight.get(), bs.weight);
    bs.pdf = simd::select(is_dielectric, pdf.get(), bs.pdf);
    bs.ok = simd::select(is_dielectric, M8::from_bits(ok), bs.ok);
    delta |= is_dielectric;
  }

  const V8 wi_world = shading.to_world(bs.wi);
  M8 going = lanes & bs.ok & !(opaque & (dot(wi_world, normal) <= F8(0.0f)));
  V8 new_beta = beta * bs.weight;
  going &= simd::max_component(new_beta) > F8(0.0f);
  if (w.reuse)
    record_reuse(w, begin, lanes & is_lambert, below, bs.ok, position, normal, shading.n, new_beta);
  // Russian roulette from russian_roulette_depth on.
  const simd::I8 depth = simd::I8::load(w.depth.data() + begin);
  const M8 roulette = (depth + simd::I8(1)) >= simd::I8(settings_.russian_roulette_depth);
  const F8 survive = simd::min(F8(0.95f), simd::max_component(new_beta));
  going = going.and_not(roulette & (u_roulette >= survive));
  new_beta = simd::select(roulette, new_beta * (1.0f / survive), new_beta);

  // The radiance cache's vertex: a Lambertian path ends into a ready cell (unless it is drawn to
  // train), or goes on marked to train its cell.
  if (cache_) {
    const M8 at_cache = is_lambert & (depth == simd::I8(settings_.quality.cache.vertex));
    if (at_cache.any()) {
      const LaneOut at(position), side(normal), albedo(base), throughput(beta);
      const LaneScalars train(load_u(kSpare));
      const RadianceCacheOptions& q = settings_.quality.cache;
      uint32_t ended = 0;
      for (uint32_t m = at_cache.bits(); m; m &= m - 1) {
        const int i = __builtin_ctz(m);
        const size_t k = begin + static_cast<size_t>(i);
        const uint32_t material = static_cast<uint32_t>(material_of[i]);
        float j0, j1;
        RadianceCache::jitter(at[i], j0, j1);
        Color incident;
        if (train[i] >= q.train &&
            cache_->lookup(at[i], side[i], material, j0, j1, q.min_samples, incident)) {
          w.add_radiance(k, throughput[i] * albedo[i] * incident);
          ended |= 1u << i;
        } else if ((going.bits() >> i) & 1) {
          w.mark_for_cache(k, cache_->key(at[i], side[i], material), throughput[i], albedo[i]);
        }
      }
      going = going.and_not(M8::from_bits(ended));
    }
  }

  // The state of the paths that go on (the others end here, their state no longer read).
  store3(PathWave::kBetaX, simd::select(going, new_beta, beta));
  store3(PathWave::kOrgX, simd::select(going, offset_ray_origin(position, normal, wi_world),
                                       load3(PathWave::kOrgX)));
  store3(PathWave::kDirX, simd::select(going, wi_world, -wo_world));
  store3(PathWave::kPrevX, simd::select(going, position, load3(PathWave::kPrevX)));
  store(PathWave::kPrevPdf, simd::select(going, bs.pdf, load(PathWave::kPrevPdf)));
  const simd::I8 flags = simd::I8::load(w.flags.data() + begin);
  // previous_was_delta = the new lobe is delta; specular_chain stays only through deltas.
  const simd::I8 delta_bits = simd::select(
      delta, simd::I8(PathWave::kPreviousWasDelta | PathWave::kSpecularChain), simd::I8(0));
  const simd::I8 new_flags(_mm256_and_si256(
      delta_bits.v, _mm256_or_si256(flags.v, _mm256_set1_epi32(PathWave::kPreviousWasDelta))));
  simd::select(going, new_flags, flags).store(w.flags.data() + begin);
  simd::select(going, depth + simd::I8(1), depth).store(w.depth.data() + begin);
  return going.bits();
}

}  // namespace tuneray
