// The five materials of MaterialType as plain functions on BsdfParams (no virtual dispatch).
//
// Conventions shared by all lobes (see bsdf.h): local frame with the normal along +z, wo and wi
// point away from the surface, eval() is f without the cosine, sample() returns
// weight = f |cos wi| / pdf. Opaque lobes live on the upper hemisphere only (the integrator
// flips the frame towards wo); the dielectric uses the sign of wo.z to know which side it is on.
//
// Choices worth knowing:
// - Mirror: weight = specular_color (Ks). A mirror with zero specular_color is black, on purpose:
//   the base colour is the diffuse albedo and has no meaning for a perfect reflector.
// - Dielectric: reflection is untinted; refraction is tinted by transmittance and scaled by
//   1 / eta'^2 (eta' = n_transmitted / n_incident seen from wo) because the integrator carries
//   radiance, which is compressed when it enters a denser medium and expands when it leaves.
// - Glossy: GGX with height-correlated Smith G2 and Schlick Fresnel (F0 = specular_color);
//   single scattering only, so rough conductors lose some energy (the tests measure how much).
// - Principled: f = base/pi (21/20) (1 - F0) (1 - (1 - cos_o)^5) (1 - (1 - cos_i)^5) + GGX coat
//   (F0 = specular_color), with F0 = max(specular_color) in the diffuse part. Light reaching the
//   diffuse base crosses the coat twice, each time losing Schlick's F; the 21/20 renormalises the
//   second crossing so the diffuse albedo is exactly base (1 - F(cos_o)), the energy the coat lets
//   in. The product is reciprocal, and diffuse + coat albedo stays <= 1 (tested). With
//   specular_color = 0 the coat is absent and the material is exactly Lambert (Schlick would
//   otherwise still add a grazing reflection, which an MTL Ks = 0 does not ask for).
// - GGX alphas are clamped to >= kMinAlpha: below that the lobe is a mirror in all but name and
//   float precision in D() runs out.
#include <algorithm>
#include <cmath>

#include "render/bsdf.h"
#include "render/sampling.h"

namespace tuneray {

namespace {

constexpr float kMinAlpha = 1e-3f;

float clamp_alpha(float a) {
  return a > kMinAlpha ? a : kMinAlpha;
}
float clamp_ior(float ior) {
  return ior > 0 && std::isfinite(ior) ? ior : 1.0f;
}

float schlick_weight(float cos_theta) {
  float m = 1.0f - std::clamp(cos_theta, 0.0f, 1.0f);
  float m2 = m * m;
  return m2 * m2 * m;
}

Vec3f mirror_direction(Vec3f wo) {
  return {-wo.x, -wo.y, wo.z};
}

// GGX reflection f and its visible-normal sampling pdf; wo and wi on the upper hemisphere.
Color ggx_reflection(Color f0, float ax, float ay, Vec3f wo, Vec3f wi, float* pdf) {
  Vec3f h = wo + wi;
  float len = length(h);
  if (!(len > 0)) {
    *pdf = 0;
    return Color(0.0f);
  }
  h = h / len;
  float d = ggx::D(h, ax, ay);
  float lambda_o = ggx::Lambda(wo, ax, ay);
  float lambda_i = ggx::Lambda(wi, ax, ay);
  // pdf = D_wo(h) / (4 wo.h) with D_wo(h) = G1(wo) (wo.h) D(h) / wo.z.
  *pdf = d / ((1.0f + lambda_o) * 4.0f * wo.z);
  float g2 = 1.0f / (1.0f + lambda_o + lambda_i);
  float h_dot_o = dot(wo, h);
  Color fresnel = f0 + (Color(1.0f) - f0) * schlick_weight(h_dot_o);
  return fresnel * (d * g2 / (4.0f * wo.z * wi.z));
}

// --- Glossy conductor ------------------------------------------------------------------------

Color glossy_eval(const BsdfParams& p, Vec3f wo, Vec3f wi, float* pdf) {
  *pdf = 0;
  if (wo.z <= 0 || wi.z <= 0) return Color(0.0f);
  return ggx_reflection(p.specular_color, clamp_alpha(p.alpha_x), clamp_alpha(p.alpha_y), wo, wi,
                        pdf);
}

bool glossy_sample(const BsdfParams& p, Vec3f wo, Vec2f u, BsdfSample& out) {
  if (wo.z <= 0) return false;
  Vec3f wh = ggx::sample_visible_normal(wo, clamp_alpha(p.alpha_x), clamp_alpha(p.alpha_y), u);
  Vec3f wi = reflect(wo, wh);
  if (wi.z <= 0) return false;
  float pdf = 0;
  Color f = glossy_eval(p, wo, wi, &pdf);
  if (!(pdf > 0)) return false;
  out.wi = wi;
  out.pdf = pdf;
  out.weight = f * (wi.z / pdf);
  out.is_delta = false;
  return true;
}

// --- Principled: diffuse base under a GGX coat ---------------------------------------------

struct PrincipledLobes {
  float f0_max;            // scalar F0 of the coat for the diffuse part; 0 = no coat
  float diffuse_o;         // wo's share of the diffuse factor (see the top of this file)
  float spec_probability;  // chance of sampling the coat; depends on wo only
};

PrincipledLobes principled_lobes(const BsdfParams& p, Vec3f wo) {
  PrincipledLobes l;
  l.f0_max = std::clamp(max_component(p.specular_color), 0.0f, 1.0f);
  const bool coat = l.f0_max > 0;
  float transmitted_o = coat ? 1.0f - schlick_weight(wo.z) : 1.0f;  // (1 - F(cos_o)) / (1 - F0)
  l.diffuse_o = coat ? (21.0f / 20.0f) * (1.0f - l.f0_max) * transmitted_o : 1.0f;
  // Albedo estimates: the coat reflects about F(cos_o), the base returns base (1 - F(cos_o)).
  float spec = coat ? 1.0f - (1.0f - l.f0_max) * transmitted_o : 0.0f;
  float diffuse = std::max(0.0f, max_component(p.base_color)) * (1.0f - spec);
  float total = spec + diffuse;
  l.spec_probability = total > 0 ? spec / total : 0.0f;
  return l;
}

Color principled_eval(const BsdfParams& p, const PrincipledLobes& l, Vec3f wo, Vec3f wi,
                      float* pdf) {
  *pdf = 0;
  if (wo.z <= 0 || wi.z <= 0) return Color(0.0f);
  float diffuse_i = l.f0_max > 0 ? 1.0f - schlick_weight(wi.z) : 1.0f;
  Color f = p.base_color * (kInvPi * l.diffuse_o * diffuse_i);
  float pdf_spec = 0;
  if (l.f0_max > 0) {
    f += ggx_reflection(p.specular_color, clamp_alpha(p.alpha_x), clamp_alpha(p.alpha_y), wo, wi,
                        &pdf_spec);
  }
  *pdf = l.spec_probability * pdf_spec + (1.0f - l.spec_probability) * wi.z * kInvPi;
  return f;
}

bool principled_sample(const BsdfParams& p, Vec3f wo, float u_lobe, Vec2f u, BsdfSample& out) {
  if (wo.z <= 0) return false;
  PrincipledLobes l = principled_lobes(p, wo);
  Vec3f wi;
  if (u_lobe < l.spec_probability) {
    Vec3f wh = ggx::sample_visible_normal(wo, clamp_alpha(p.alpha_x), clamp_alpha(p.alpha_y), u);
    wi = reflect(wo, wh);
  } else if (l.spec_probability < 1.0f) {
    wi = sample_cosine_hemisphere(u);
  } else {
    return false;
  }
  if (wi.z <= 0) return false;
  float pdf = 0;
  Color f = principled_eval(p, l, wo, wi, &pdf);
  if (!(pdf > 0)) return false;
  out.wi = wi;
  out.pdf = pdf;
  out.weight = f * (wi.z / pdf);
  out.is_delta = false;
  return true;
}

// --- Smooth dielectric ------------------------------------------------------------------------

bool dielectric_sample(const BsdfParams& p, Vec3f wo, float u_lobe, BsdfSample& out) {
  float cos_o = wo.z;
  if (cos_o == 0 || !std::isfinite(cos_o)) return false;
  float ior = clamp_ior(p.ior);
  float reflectance = fresnel_dielectric(cos_o, ior);
  out.is_delta = true;
  if (u_lobe < reflectance) {
    out.wi = mirror_direction(wo);
    out.weight = Color(1.0f);
    out.pdf = reflectance;
    return true;
  }
  float eta = cos_o > 0 ? ior : 1.0f / ior;  // n_transmitted / n_incident
  float sin2_t = (1.0f - cos_o * cos_o) / (eta * eta);
  float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin2_t));
  out.wi = Vec3f(-wo.x / eta, -wo.y / eta, cos_o > 0 ? -cos_t : cos_t);
  out.weight = p.transmittance * (1.0f / (eta * eta));
  out.pdf = 1.0f - reflectance;
  return true;
}

}  // namespace

Color bsdf_eval(const BsdfParams& p, Vec3f wo, Vec3f wi) {
  float pdf = 0;
  switch (p.type) {
    case MaterialType::kLambert:
      return wo.z > 0 && wi.z > 0 ? p.base_color * kInvPi : Color(0.0f);
    case MaterialType::kGlossy:
      return glossy_eval(p, wo, wi, &pdf);
    case MaterialType::kPrincipled:
      if (wo.z <= 0 || wi.z <= 0) return Color(0.0f);
      return principled_eval(p, principled_lobes(p, wo), wo, wi, &pdf);
    case MaterialType::kMirror:
    case MaterialType::kDielectric:
      break;
  }
  return Color(0.0f);
}

float bsdf_pdf(const BsdfParams& p, Vec3f wo, Vec3f wi) {
  float pdf = 0;
  switch (p.type) {
    case MaterialType::kLambert:
      return wo.z > 0 ? cosine_hemisphere_pdf(wi.z) : 0.0f;
    case MaterialType::kGlossy:
      glossy_eval(p, wo, wi, &pdf);
      return pdf;
    case MaterialType::kPrincipled:
      if (wo.z <= 0 || wi.z <= 0) return 0.0f;
      principled_eval(p, principled_lobes(p, wo), wo, wi, &pdf);
      return pdf;
    case MaterialType::kMirror:
    case MaterialType::kDielectric:
      break;
  }
  return 0.0f;
}

bool bsdf_sample(const BsdfParams& p, Vec3f wo, float u_lobe, Vec2f u, BsdfSample& out) {
  switch (p.type) {
    case MaterialType::kLambert: {
      if (wo.z <= 0) return false;
      Vec3f wi = sample_cosine_hemisphere(u);
      if (wi.z <= 0) return false;
      out.wi = wi;
      out.pdf = cosine_hemisphere_pdf(wi.z);
      out.weight = p.base_color;  // (base / pi) cos / (cos / pi)
      out.is_delta = false;
      return true;
    }
    case MaterialType::kMirror:
      if (wo.z <= 0) return false;
      out.wi = mirror_direction(wo);
      out.weight = p.specular_color;
      out.pdf = 1.0f;
      out.is_delta = true;
      return true;
    case MaterialType::kDielectric:
      return dielectric_sample(p, wo, u_lobe, out);
    case MaterialType::kGlossy:
      return glossy_sample(p, wo, u, out);
    case MaterialType::kPrincipled:
      return principled_sample(p, wo, u_lobe, u, out);
  }
  return false;
}

BsdfEval bsdf_evaluate_by_type(const BsdfParams& p, Vec3f wo, Vec3f wi) {
  BsdfEval e;
  switch (p.type) {
    case MaterialType::kLambert:
      e.f = wo.z > 0 && wi.z > 0 ? p.base_color * kInvPi : Color(0.0f);
      e.pdf = wo.z > 0 ? cosine_hemisphere_pdf(wi.z) : 0.0f;
      break;
    case MaterialType::kGlossy:
      e.f = glossy_eval(p, wo, wi, &e.pdf);
      break;
    case MaterialType::kPrincipled:
      if (wo.z > 0 && wi.z > 0) e.f = principled_eval(p, principled_lobes(p, wo), wo, wi, &e.pdf);
      break;
    case MaterialType::kMirror:
    case MaterialType::kDielectric:
      break;
  }
  return e;
}

BsdfEval bsdf_evaluate(const BsdfParams& p, Vec3f wo, Vec3f wi) {
  // Lobe weights from the type: Lambert = diffuse only, glossy = GGX only (F0 = Ks, sampled
  // always), principled = diffuse under a GGX coat when max(Ks) > 0, else exactly Lambert.
  const bool lambert = p.type == MaterialType::kLambert;
  const bool glossy = p.type == MaterialType::kGlossy;
  const bool principled = p.type == MaterialType::kPrincipled;
  const bool valid = (lambert | glossy | principled) & (wo.z > 0) & (wi.z > 0);
  // Invalid inputs get harmless stand-ins so nothing below produces inf/NaN; the result is
  // zeroed at the end.
  const Vec3f o = valid ? wo : Vec3f(0, 0, 1);
  const Vec3f i = valid ? wi : Vec3f(0, 0, 1);

  const float f0_max = std::clamp(max_component(p.specular_color), 0.0f, 1.0f);
  const bool coat = principled & (f0_max > 0);
  const float transmitted_o = coat ? 1.0f - schlick_weight(o.z) : 1.0f;
  const float diffuse_o = coat ? (21.0f / 20.0f) * (1.0f - f0_max) * transmitted_o : 1.0f;
  const float diffuse_i = coat ? 1.0f - schlick_weight(i.z) : 1.0f;
  const float spec_albedo = coat ? 1.0f - (1.0f - f0_max) * transmitted_o : 0.0f;
  const float total =
      spec_albedo + std::max(0.0f, max_component(p.base_color)) * (1.0f - spec_albedo);
  const float coat_probability = total > 0 ? spec_albedo / total : 0.0f;
  const float spec_probability = glossy ? 1.0f : coat_probability;
  const float diffuse_weight = glossy ? 0.0f : kInvPi * diffuse_o * diffuse_i;
  const bool has_spec = glossy | coat;

  // GGX reflection, as ggx_reflection() with D and the Lambdas inlined.
  const float ax = clamp_alpha(p.alpha_x), ay = clamp_alpha(p.alpha_y);
  Vec3f h = o + i;
  h = h / length(h);  // > 0: both on the upper hemisphere
  const float hx = h.x / ax, hy = h.y / ay;
  const float s = hx * hx + hy * hy + h.z * h.z;
  const float d = 1.0f / (kPi * ax * ay * s * s);
  const float ax2 = ax * ax, ay2 = ay * ay;
  const float lambda_o =
      0.5f * (std::sqrt(1.0f + (ax2 * o.x * o.x + ay2 * o.y * o.y) / (o.z * o.z)) - 1.0f);
  const float lambda_i =
      0.5f * (std::sqrt(1.0f + (ax2 * i.x * i.x + ay2 * i.y * i.y) / (i.z * i.z)) - 1.0f);
  const float pdf_spec = d / ((1.0f + lambda_o) * 4.0f * o.z);
  const float g2 = 1.0f / (1.0f + lambda_o + lambda_i);
  const Color fresnel =
      p.specular_color + (Color(1.0f) - p.specular_color) * schlick_weight(dot(o, h));
  const Color f_spec = fresnel * (d * g2 / (4.0f * o.z * i.z));

  BsdfEval e;
  // Selects, not products with 0: at grazing angles the unused GGX terms may be inf/NaN.
  const Color f_diffuse = p.base_color * diffuse_weight;
  const float pdf_diffuse = i.z * kInvPi;
  e.f = has_spec ? f_diffuse + f_spec : f_diffuse;
  e.pdf = has_spec ? spec_probability * pdf_spec + (1.0f - spec_probability) * pdf_diffuse
                   : pdf_diffuse;
  e.f = valid ? e.f : Color(0.0f);
  e.pdf = valid ? e.pdf : 0.0f;
  return e;
}

bool bsdf_has_smooth_lobe(const BsdfParams& p) {
  return p.type == MaterialType::kLambert || p.type == MaterialType::kGlossy ||
         p.type == MaterialType::kPrincipled;
}

}  // namespace tuneray
