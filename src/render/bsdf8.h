// The smooth BSDFs of bsdf.h for eight shading points at once (render/shade8.h): Lambert, the
// GGX conductor ("glossy") and the principled diffuse-under-coat, in the local shading frame,
// lane by lane the same formulas as the scalar functions (test_bsdf8.cpp compares them on random
// inputs). Delta lobes (mirror, dielectric) are not here: the caller samples them per lane.
#pragma once

#include "render/simd8.h"

namespace tuneray::simd {

inline constexpr float kMinAlpha8 = 1e-3f;  // bsdf.cpp's kMinAlpha

// Per-lane parameters of the three smooth lobes (a BsdfParams per lane, as planes).
struct SmoothBsdf8 {
  M8 lambert, glossy, principled;  // the lane's type (exactly one set in a shaded lane)
  V8 base, specular;
  F8 ax, ay;  // GGX roughness, already clamped to >= kMinAlpha8
};

struct BsdfEval8 {
  V8 f;
  F8 pdf;
};

inline F8 schlick_weight(F8 cos_theta) {
  F8 m = 1.0f - min(max(cos_theta, F8(0.0f)), F8(1.0f));
  F8 m2 = m * m;
  return m2 * m2 * m;
}

// Malley's method on the concentric disk, as sample_cosine_hemisphere.
inline V8 sample_cosine_hemisphere(F8 ux, F8 uy) {
  const F8 a = 2.0f * ux - 1.0f, b = 2.0f * uy - 1.0f;
  const M8 centre = (a == F8(0.0f)) & (b == F8(0.0f));
  const M8 horizontal = abs(a) > abs(b);
  const F8 r = select(horizontal, a, b);
  const F8 phi = (kPi / 4) * (select(horizontal, b, a) / select(centre, F8(1.0f), r));
  const F8 phi2 = phi * phi;
  const F8 s =
      phi * (1.0f - phi2 * (1.0f / 6) *
                        (1.0f - phi2 * (1.0f / 20) *
                                    (1.0f - phi2 * (1.0f / 42) * (1.0f - phi2 * (1.0f / 72)))));
  const F8 c =
      1.0f -
      phi2 * 0.5f *
          (1.0f - phi2 * (1.0f / 12) *
                      (1.0f - phi2 * (1.0f / 30) *
                                  (1.0f - phi2 * (1.0f / 56) * (1.0f - phi2 * (1.0f / 90)))));
  F8 dx = r * select(horizontal, c, s), dy = r * select(horizontal, s, c);
  dx = keep(!centre, dx);
  dy = keep(!centre, dy);
  const F8 z = sqrt(max(F8(0.0f), 1.0f - dx * dx - dy * dy));
  return {dx, dy, z};
}

// ggx::D, ggx::Lambda for unit vectors.
inline F8 ggx_D(const V8& wh, F8 ax, F8 ay) {
  const F8 x = wh.x / ax, y = wh.y / ay;
  const F8 s = x * x + y * y + wh.z * wh.z;
  return select(wh.z <= F8(0.0f), F8(0.0f), 1.0f / (kPi * ax * ay * s * s));
}
inline F8 ggx_Lambda(const V8& w, F8 ax, F8 ay) {
  const F8 z2 = w.z * w.z;
  const F8 t = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / z2;
  return select(z2 <= F8(0.0f), F8(kInf), 0.5f * (sqrt(1.0f + t) - 1.0f));
}

// ggx::sample_visible_normal (Heitz 2018).
inline V8 ggx_sample_visible_normal(const V8& wo, F8 ax, F8 ay, F8 ux, F8 uy) {
  const V8 vh = normalize(V8(ax * wo.x, ay * wo.y, wo.z));
  const F8 len2 = vh.x * vh.x + vh.y * vh.y;
  const M8 tilted = len2 > F8(0.0f);
  const F8 inv_len = 1.0f / sqrt(select(tilted, len2, F8(1.0f)));
  const V8 t1(select(tilted, -vh.y * inv_len, F8(1.0f)), select(tilted, vh.x * inv_len, F8(0.0f)),
              F8(0.0f));
  const V8 t2 = cross(vh, t1);
  const F8 r = sqrt(ux);
  F8 sin_phi, cos_phi;
  sincos_turn(uy, sin_phi, cos_phi);
  const F8 p1 = r * cos_phi;
  F8 p2 = r * sin_phi;
  const F8 s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(F8(0.0f), 1.0f - p1 * p1)) + s * p2;
  const V8 nh = t1 * p1 + t2 * p2 + vh * sqrt(max(F8(0.0f), 1.0f - p1 * p1 - p2 * p2));
  return normalize(V8(ax * nh.x, ay * nh.y, max(F8(1e-7f), nh.z)));
}

inline V8 reflect(const V8& wo, const V8& n) {
  return n * (2.0f * dot(wo, n)) - wo;
}

// GGX reflection f and its visible-normal pdf (bsdf.cpp's ggx_reflection); wo, wi upper.
inline BsdfEval8 ggx_reflection(const V8& f0, F8 ax, F8 ay, const V8& wo, const V8& wi) {
  V8 h = wo + wi;
  const F8 len = length(h);
  const M8 ok = len > F8(0.0f);
  h = h / select(ok, len, F8(1.0f));
  const F8 d = ggx_D(h, ax, ay);
  const F8 lambda_o = ggx_Lambda(wo, ax, ay);
  const F8 lambda_i = ggx_Lambda(wi, ax, ay);
  BsdfEval8 e;
  e.pdf = keep(ok, d / ((1.0f + lambda_o) * 4.0f * wo.z));
  const F8 g2 = 1.0f / (1.0f + lambda_o + lambda_i);
  const F8 w = schlick_weight(dot(wo, h));
  const V8 fresnel = f0 + (V8(F8(1.0f)) - f0) * w;
  e.f = keep(ok, fresnel * (d * g2 / (4.0f * wo.z * wi.z)));
  return e;
}

// principled_lobes: what the principled material's f and pdf need of wo.
struct PrincipledLobes8 {
  F8 f0_max, diffuse_o, spec_probability;
  M8 coat;
};
inline PrincipledLobes8 principled_lobes(const SmoothBsdf8& p, const V8& wo) {
  PrincipledLobes8 l;
  l.f0_max = min(max(max_component(p.specular), F8(0.0f)), F8(1.0f));
  l.coat = l.f0_max > F8(0.0f);
  const F8 transmitted_o = select(l.coat, 1.0f - schlick_weight(wo.z), F8(1.0f));
  l.diffuse_o = select(l.coat, (21.0f / 20.0f) * (1.0f - l.f0_max) * transmitted_o, F8(1.0f));
  const F8 spec = select(l.coat, 1.0f - (1.0f - l.f0_max) * transmitted_o, F8(0.0f));
  const F8 diffuse = max(F8(0.0f), max_component(p.base)) * (1.0f - spec);
  const F8 total = spec + diffuse;
  l.spec_probability = select(total > F8(0.0f), spec / total, F8(0.0f));
  return l;
}

// f and pdf of the principled material for wo, wi on the upper hemisphere.
inline BsdfEval8 principled_eval(const SmoothBsdf8& p, const PrincipledLobes8& l, const V8& wo,
                                 const V8& wi) {
  const F8 diffuse_i = select(l.coat, 1.0f - schlick_weight(wi.z), F8(1.0f));
  BsdfEval8 spec = ggx_reflection(p.specular, p.ax, p.ay, wo, wi);
  BsdfEval8 e;
  e.f = p.base * (kInvPi * l.diffuse_o * diffuse_i) + keep(l.coat, spec.f);
  const F8 pdf_spec = keep(l.coat, spec.pdf);
  e.pdf = l.spec_probability * pdf_spec + (1.0f - l.spec_probability) * wi.z * kInvPi;
  return e;
}

// bsdf_evaluate_by_type for the smooth types: f (without the cosine) and the pdf of wi.
inline BsdfEval8 evaluate(const SmoothBsdf8& p, const V8& wo, const V8& wi) {
  const M8 upper_o = wo.z > F8(0.0f), upper_i = wi.z > F8(0.0f);
  const M8 both = upper_o & upper_i;
  BsdfEval8 e;
  e.f = keep(p.lambert & both, p.base * kInvPi);
  e.pdf = keep(p.lambert & both, wi.z * kInvPi);
  const M8 glossy = p.glossy & both, principled = p.principled & both;
  if ((glossy | principled).any()) {
    // Both GGX users in one pass: the glossy lanes are the coat alone (f0 = specular_color).
    const PrincipledLobes8 l = principled_lobes(p, wo);
    const BsdfEval8 pe = principled_eval(p, l, wo, wi);
    const BsdfEval8 ge = ggx_reflection(p.specular, p.ax, p.ay, wo, wi);
    e.f = select(glossy, ge.f, select(principled, pe.f, e.f));
    e.pdf = select(glossy, ge.pdf, select(principled, pe.pdf, e.pdf));
  }
  return e;
}

struct BsdfSample8 {
  M8 ok;  // a sample exists (else the path ends)
  V8 wi, weight;
  F8 pdf;
};

// bsdf_sample for the smooth types (lanes of other types come back with ok clear).
inline BsdfSample8 sample(const SmoothBsdf8& p, const V8& wo, F8 u_lobe, F8 ux, F8 uy) {
  BsdfSample8 s;
  const M8 upper_o = wo.z > F8(0.0f);
  const V8 cosine = sample_cosine_hemisphere(ux, uy);
  s.wi = cosine;
  s.weight = p.base;
  s.pdf = select(cosine.z > F8(0.0f), cosine.z * kInvPi, F8(0.0f));
  s.ok = p.lambert & upper_o & (cosine.z > F8(0.0f));
  const M8 ggx = (p.glossy | p.principled) & upper_o;
  if (!ggx.any()) return s;

  const PrincipledLobes8 l = principled_lobes(p, wo);
  const V8 wh = ggx_sample_visible_normal(wo, p.ax, p.ay, ux, uy);
  const V8 reflected = reflect(wo, wh);
  // Glossy always samples the coat; principled picks it with its probability, else diffuse.
  const M8 spec_lobe = p.glossy | (u_lobe < l.spec_probability);
  const M8 diffuse_possible = l.spec_probability < F8(1.0f);
  const V8 wi = select(spec_lobe, reflected, cosine);
  const M8 chosen = ggx & (spec_lobe | diffuse_possible) & (wi.z > F8(0.0f));
  const BsdfEval8 ge = ggx_reflection(p.specular, p.ax, p.ay, wo, wi);
  const BsdfEval8 pe = principled_eval(p, l, wo, wi);
  const V8 f = select(p.glossy, ge.f, pe.f);
  const F8 pdf = select(p.glossy, ge.pdf, pe.pdf);
  const M8 valid = chosen & (pdf > F8(0.0f));
  s.wi = select(ggx, wi, s.wi);
  s.pdf = select(ggx, pdf, s.pdf);
  s.weight = select(ggx, f * (wi.z / select(valid, pdf, F8(1.0f))), s.weight);
  s.ok = select(ggx, valid, s.ok);
  return s;
}

}  // namespace tuneray::simd
