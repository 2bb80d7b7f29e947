// BSDFs in the local shading frame (normal = +z). All directions point away from the surface.
// eval() returns f(wo, wi) WITHOUT the cosine; sample() returns weight = f |cos wi| / pdf.
// Delta lobes (mirror, smooth dielectric) are only reachable through sample(); eval/pdf return 0
// for them.
#pragma once

#include "math/vec.h"
#include "render/ggx.h"  // the GGX pieces, inline; exposed for tests
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
// The per-type reference for bsdf_evaluate: exactly bsdf_eval's f and bsdf_pdf's pdf, from one
// call of the type's function (which computes both; called one after the other, the GGX terms
// were computed twice).
BsdfEval bsdf_evaluate_by_type(const BsdfParams& p, Vec3f wo, Vec3f wi);

// True if the BSDF has any non-delta component (next-event estimation is worth doing).
bool bsdf_has_smooth_lobe(const BsdfParams& p);

// Dielectric Fresnel reflectance for cos_i (signed: negative = from inside) and eta = n_t / n_i
// of the outside/inside pair (ior).
float fresnel_dielectric(float cos_i, float ior);
inline Color fresnel_schlick(Color f0, float cos_theta) {
  float m = 1.0f - cos_theta;
  float m5 = m * m * m * m * m;
  return f0 + (Color(1.0f) - f0) * m5;
}

}  // namespace tuneray
