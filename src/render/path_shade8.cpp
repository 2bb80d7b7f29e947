// PathIntegrator::shade8: the shading step of up to eight paths at once. The math that every
// bounce does (hit point and frames, BSDF evaluation and sampling, MIS, Russian roulette, the
// next ray) runs in AVX2 lanes; what is rare or table-driven (misses and the environment,
// emitters, textures, light selection, the dielectric) runs per lane with the scalar code.
// Every step is lane by lane, so a path's result does not depend on its neighbours.
#include <algorithm>
#include <cmath>

#include "render/bsdf8.h"
#include "render/path_integrator.h"
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

}  // namespace

void PathIntegrator::shade8(ShadeBatch& b) const {
  const bool use_nee = settings_.strategy != LightStrategy::kBsdfOnly;
  const bool mis = settings_.strategy == LightStrategy::kMis;

  // --- Per lane: misses, emission, the end of the path; gathering for the lanes that scatter.
  uint32_t scatter = 0;
  BsdfParams params[kLanes];
  LaneVecs p0, p1, p2, n0, n1, n2, ng, flat_normal, flat_tangent;
  LaneFloats bu, bv;
  uint32_t flat = 0;
  for (int i = 0; i < b.count; ++i) {
    PathState& st = *b.state[i];
    b.shadow[i].active = false;
    const Hit& hit = b.hit[i];
    if (!hit.valid()) {
      shade_miss(st);
      continue;
    }
    const TriangleShading& ts = geometry_.triangle(hit.prim);
    const Material& material = scene_.materials[ts.material];
    if (material.is_emissive()) add_emission(st, hit);
    if (st.depth >= settings_.max_bounces) {
      st.alive = false;
      continue;
    }
    scatter |= 1u << i;
    const Triangle& tri = scene_.triangles[hit.prim];
    const Vec3f a = scene_.positions[tri.v[0]], c = scene_.positions[tri.v[1]],
                d = scene_.positions[tri.v[2]];
    p0.set(i, a);
    p1.set(i, c);
    p2.set(i, d);
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
    params[i] = material_bsdf_[ts.material];
    if (material.base_texture != kNoTexture) {
      // resolve_bsdf's lookup: at the interpolated UV, or (0, 0) on a mesh without UVs.
      Vec2f uv;
      if (!scene_.uvs.empty()) {
        const float w0 = 1.0f - hit.u - hit.v;
        uv =
            scene_.uvs[tri.v[0]] * w0 + scene_.uvs[tri.v[1]] * hit.u + scene_.uvs[tri.v[2]] * hit.v;
      }
      params[i].base_color *= texture_factor(scene_, material, uv);
    }
    if (settings_.quality.regularize) regularize(params[i], st.max_roughness);
  }
  if (!scatter) return;

  // --- The hit point and its frames (ShadingGeometry::interaction and facing_frame), 8 wide.
  const M8 lanes = M8::from_bits(scatter);
  const F8 u = bu.get(), v = bv.get(), w0 = 1.0f - u - v;
  const V8 a = p0.get(), c = p1.get(), d = p2.get();
  const V8 position = a * w0 + c * u + d * v;
  V8 normal = ng.get();
  Frame8 shading;
  const M8 is_flat = M8::from_bits(flat);
  if (flat) {
    const V8 fn = flat_normal.get(), ft = flat_tangent.get();
    shading = {ft, cross(fn, ft), fn};
  }
  if (scatter & ~flat) {
    V8 ns = n0.get() * w0 + n1.get() * u + n2.get() * v;
    const F8 ns_len = length(ns);
    const M8 ok = (ns_len > F8(0.0f)) & simd::is_finite(ns_len);
    ns = simd::select(ok, ns / simd::select(ok, ns_len, F8(1.0f)), normal);
    const Frame8 smooth = frame_from_normal_tangent(ns, c - a);
    shading.s = simd::select(is_flat, shading.s, smooth.s);
    shading.t = simd::select(is_flat, shading.t, smooth.t);
    shading.n = simd::select(is_flat, shading.n, smooth.n);
  }

  LaneVecs dir_in;
  uint32_t opaque_bits = 0, smooth_bits = 0;
  simd::SmoothBsdf8 bsdf;
  LaneVecs base, specular;
  LaneFloats ax, ay;
  uint32_t lambert = 0, glossy = 0, principled = 0, mirror = 0;
  for (uint32_t m = scatter; m; m &= m - 1) {
    const int i = __builtin_ctz(m);
    const BsdfParams& p = params[i];
    dir_in.set(i, b.state[i]->ray.dir);
    const uint32_t bit = 1u << i;
    if (p.type != MaterialType::kDielectric) opaque_bits |= bit;
    if (bsdf_has_smooth_lobe(p)) smooth_bits |= bit;
    switch (p.type) {
      case MaterialType::kLambert:
        lambert |= bit;
        break;
      case MaterialType::kGlossy:
        glossy |= bit;
        break;
      case MaterialType::kPrincipled:
        principled |= bit;
        break;
      case MaterialType::kMirror:
        mirror |= bit;
        break;
      case MaterialType::kDielectric:
        break;
    }
    base.set(i, p.base_color);
    specular.set(i, p.specular_color);
    // bsdf.cpp's clamp_alpha: a NaN roughness becomes the minimum too.
    ax.v[i] = p.alpha_x > simd::kMinAlpha8 ? p.alpha_x : simd::kMinAlpha8;
    ay.v[i] = p.alpha_y > simd::kMinAlpha8 ? p.alpha_y : simd::kMinAlpha8;
  }
  bsdf.lambert = M8::from_bits(lambert);
  bsdf.glossy = M8::from_bits(glossy);
  bsdf.principled = M8::from_bits(principled);
  bsdf.base = base.get();
  bsdf.specular = specular.get();
  bsdf.ax = ax.get();
  bsdf.ay = ay.get();

  const M8 opaque = M8::from_bits(opaque_bits);
  const V8 wo_world = -dir_in.get();
  // facing_frame: opaque BSDFs see the side of the surface that wo is on.
  const M8 flip = opaque & (dot(normal, wo_world) < F8(0.0f));
  normal = simd::select(flip, -normal, normal);
  shading.t = simd::select(flip, -shading.t, shading.t);
  shading.n = simd::select(flip, -shading.n, shading.n);
  const M8 below = lanes & opaque & (dot(shading.n, wo_world) <= F8(1e-6f));
  if (below.any()) {
    const Frame8 g = frame_from_normal_tangent(normal, shading.s);
    shading.s = simd::select(below, g.s, shading.s);
    shading.t = simd::select(below, g.t, shading.t);
    shading.n = simd::select(below, g.n, shading.n);
  }
  const V8 wo = shading.to_local(wo_world);

  LaneFloats u_light3, u_bsdf0, u_bsdf1, u_bsdf2;
  for (uint32_t m = scatter; m; m &= m - 1) {
    const int i = __builtin_ctz(m);
    u_light3.v[i] = b.u[i].light[3];
    u_bsdf0.v[i] = b.u[i].bsdf[0];
    u_bsdf1.v[i] = b.u[i].bsdf[1];
    u_bsdf2.v[i] = b.u[i].bsdf[2];
  }

  // --- Next-event estimation: the light sample per lane, its evaluation 8 wide.
  LaneVecs beta_in;
  for (uint32_t m = scatter; m; m &= m - 1) {
    const int i = __builtin_ctz(m);
    beta_in.set(i, b.state[i]->beta);
  }
  const V8 beta = beta_in.get();
  const LaneOut position_out(position), normal_out(normal);
  uint32_t nee = use_nee && !lights_.empty() ? smooth_bits : 0;
  if (nee) {
    LaneFloats u0, u1, u2;
    for (uint32_t m = nee; m; m &= m - 1) {
      const int i = __builtin_ctz(m);
      u0.v[i] = b.u[i].light[0];
      u1.v[i] = b.u[i].light[1];
      u2.v[i] = b.u[i].light[2];
    }
    LightSample8 ls = lights_.sample8(position, u0.get(), u1.get(), u2.get(), nee);
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
    const uint32_t delta = ls.is_delta.bits();
    if (nee) {
      const V8 wi_world = ls.wi;
      const V8 wi = shading.to_local(wi_world);
      simd::BsdfEval8 e;
      if (settings_.quality.branchless_materials) {
        // The branch-reduced formula (technique 4) stays the scalar one, lane by lane.
        const LaneOut wo_out(wo), wi_out(wi);
        LaneVecs f;
        LaneFloats pdf;
        for (uint32_t m = nee; m; m &= m - 1) {
          const int i = __builtin_ctz(m);
          const BsdfEval s = bsdf_evaluate(params[i], wo_out[i], wi_out[i]);
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
        const F8 lpdf = ls.pdf, ldist = ls.distance;
        const V8 org = offset_ray_origin(position, normal, wi_world);
        const F8 tfar = simd::select(ldist < F8(kInf), ldist * (1.0f - 1e-4f), F8(kInf));
        F8 w(1.0f);
        if (mis) w = simd::select(M8::from_bits(delta), w, power_heuristic(lpdf, e.pdf));
        const V8 contribution = beta * e.f * ls.radiance * (simd::abs(wi.z) * w / lpdf);
        const LaneOut org_out(org), dir_out(wi_world), contribution_out(contribution);
        const LaneScalars tfar_out(tfar);
        for (uint32_t m = lit.bits(); m; m &= m - 1) {
          const int i = __builtin_ctz(m);
          ShadowRequest& sr = b.shadow[i];
          sr.ray = Ray{};
          sr.ray.org = org_out[i];
          sr.ray.dir = dir_out[i];
          sr.ray.tfar = tfar_out[i];
          sr.contribution = contribution_out[i];
          sr.active = true;
        }
      }
    }
  }

  // --- The next direction: smooth lobes 8 wide, the delta lobes per lane.
  simd::BsdfSample8 bs = simd::sample(bsdf, wo, u_light3.get(), u_bsdf0.get(), u_bsdf1.get());
  M8 delta = M8::none();
  if (mirror) {
    const M8 mm = M8::from_bits(mirror);
    const M8 ok = mm & (wo.z > F8(0.0f));
    bs.wi = simd::select(mm, V8(-wo.x, -wo.y, wo.z), bs.wi);
    bs.weight = simd::select(mm, bsdf.specular, bs.weight);
    bs.pdf = simd::select(mm, F8(1.0f), bs.pdf);
    bs.ok = simd::select(mm, ok, bs.ok);
    delta |= mm;
  }
  const uint32_t dielectric = scatter & ~opaque_bits;
  if (dielectric) {
    const LaneOut wo_out(wo);
    LaneVecs wi, weight;
    LaneFloats pdf;
    uint32_t ok = 0;
    for (uint32_t m = dielectric; m; m &= m - 1) {
      const int i = __builtin_ctz(m);
      BsdfSample s;
      if (bsdf_sample(params[i], wo_out[i], b.u[i].light[3], {b.u[i].bsdf[0], b.u[i].bsdf[1]}, s))
        ok |= 1u << i;
      wi.set(i, s.wi);
      weight.set(i, s.weight);
      pdf.v[i] = s.pdf;
    }
    const M8 dm = M8::from_bits(dielectric);
    bs.wi = simd::select(dm, wi.get(), bs.wi);
    bs.weight = simd::select(dm, weight.get(), bs.weight);
    bs.pdf = simd::select(dm, pdf.get(), bs.pdf);
    bs.ok = simd::select(dm, M8::from_bits(ok), bs.ok);
    delta |= dm;
  }

  const V8 wi_world = shading.to_world(bs.wi);
  M8 going = lanes & bs.ok & !(opaque & (dot(wi_world, normal) <= F8(0.0f)));
  V8 new_beta = beta * bs.weight;
  going &= simd::max_component(new_beta) > F8(0.0f);
  // Russian roulette from russian_roulette_depth on.
  LaneFloats depth_in;
  for (uint32_t m = scatter; m; m &= m - 1) {
    const int i = __builtin_ctz(m);
    depth_in.v[i] = static_cast<float>(b.state[i]->depth + 1);
  }
  const M8 roulette = depth_in.get() >= F8(static_cast<float>(settings_.russian_roulette_depth));
  const F8 survive = simd::min(F8(0.95f), simd::max_component(new_beta));
  going = going.and_not(roulette & (u_bsdf2.get() >= survive));
  new_beta = simd::select(roulette, new_beta * (1.0f / survive), new_beta);
  const V8 org = offset_ray_origin(position, normal, wi_world);

  const LaneOut beta_out(new_beta), org_out(org), dir_out(wi_world);
  const LaneScalars pdf_out(bs.pdf);
  const uint32_t going_bits = going.bits(), delta_bits = delta.bits();
  for (uint32_t m = scatter; m; m &= m - 1) {
    const int i = __builtin_ctz(m);
    PathState& st = *b.state[i];
    const uint32_t bit = 1u << i;
    if (!(going_bits & bit)) {
      st.alive = false;
      continue;
    }
    const bool is_delta = (delta_bits & bit) != 0;
    st.beta = beta_out[i];
    st.previous_was_delta = is_delta;
    st.specular_chain = st.specular_chain && is_delta;
    st.previous_pdf = pdf_out[i];
    st.previous_position = position_out[i];
    st.ray = Ray{};
    st.ray.org = org_out[i];
    st.ray.dir = dir_out[i];
    ++st.depth;
    st.alive = true;
  }
}

}  // namespace tuneray
