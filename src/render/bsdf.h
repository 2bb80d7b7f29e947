// BSDFs in the local shading frame (normal = +z). All directions point away from the surface.
// eval() returns f(wo, wi) WITHOUT the cosine; sample() returns weight = f |cos wi| / pdf.
// Delta lobes (mirror, smooth dielectric) are only reachable through sample(); eval/pdf return 0
// for them.
#pragma once

#include "math/vec.h"
#include "scene/material.h"

namespace tuneray {

// A material resolved at a hit point (textures looked up, emission stripped).
struct BsdfParams {
  MaterialType type = MaterialType::kLambert;
  Color base_color{0.8f};
  Color specular_color{0.0f};
  Color transmittance{1.0f};
  float alpha_x = 0.5f;  // GGX roughness along local x
  float alpha_y = 0.5f;  // along local y
  float ior = 1.5f;
};

struct BsdfSample {
  Vec3f wi;
  Color weight{0.0f};     // f |cos wi| / pdf (for delta lobes: the lobe's throughput)
  float pdf = 0;          // solid-angle pdf; for delta lobes the discrete probability of the lobe
  bool is_delta = false;  // true when wi came from a Dirac lobe (no MIS with light sampling)
};

Color bsdf_eval(const BsdfParams& p, Vec3f wo, Vec3f wi);
float bsdf_pdf(const BsdfParams& p, Vec3f wo, Vec3f wi);
// u_lobe selects a lobe (principled, dielectric), u a direction. Returns false when no valid
// sample exists (e.g. below the horizon); then the path ends.
bool bsdf_sample(const BsdfParams& p, Vec3f wo, float u_lobe, Vec2f u, BsdfSample& out);

// f (without the cosine) and the solid-angle pdf of sampling wi, together.
struct BsdfEval {
  Color f{0.0f};
  float pdf = 0;
};
// The same values as bsdf_eval and bsdf_pdf (to float rounding), computed in one straight-line
// pass: Lambert, glossy and principled are one diffuse + GGX formula whose lobe weights are
// selected by the type, so the shared terms (half vector, Schlick weights, Smith Lambdas) are
// computed once and there are no type branches (docs/quality.md, technique 4).
BsdfEval bsdf_evaluate(const BsdfParams& p, Vec3f wo, Vec3f wi);
// The per-type reference for bsdf_evaluate: bsdf_eval and bsdf_pdf called one after the other.
inline BsdfEval bsdf_evaluate_by_type(const BsdfParams& p, Vec3f wo, Vec3f wi) {
  return {bsdf_eval(p, wo, wi), bsdf_pdf(p, wo, wi)};
}

// True if the BSDF has any non-delta component (next-event estimation is worth doing).
bool bsdf_has_smooth_lobe(const BsdfParams& p);

// GGX microfacet pieces (anisotropic), exposed for tests.
namespace ggx {
float D(Vec3f wh, float ax, float ay);
float Lambda(Vec3f w, float ax, float ay);
float G1(Vec3f w, float ax, float ay);
float G2(Vec3f wo, Vec3f wi, float ax, float ay);
// Samples a visible normal (Heitz 2018) for wo in the upper hemisphere; pdf of wh is
// G1(wo) max(0, wo.wh) D(wh) / wo.z.
Vec3f sample_visible_normal(Vec3f wo, float ax, float ay, Vec2f u);
}  // namespace ggx

// Dielectric Fresnel reflectance for cos_i (signed: negative = from inside) and eta = n_t / n_i
// of the outside/inside pair (ior).
float fresnel_dielectric(float cos_i, float ior);
inline Color fresnel_schlick(Color f0, float cos_theta) {
  float m = 1.0f - cos_theta;
  float m5 = m * m * m * m * m;
  return f0 + (Color(1.0f) - f0) * m5;
}

}  // namespace tuneray
