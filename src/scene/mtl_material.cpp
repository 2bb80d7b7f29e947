#include "scene/mtl_material.h"

#include <algorithm>
#include <cmath>

namespace tuneray {

namespace {

bool is_zero(Color c) {
  return max_component(c) <= 0.0f;
}

MaterialType type_for_illum(const MtlParams& p) {
  if (p.dissolve < 1.0f) return MaterialType::kDielectric;
  switch (p.illum) {
    case 0:
    case 1:
      return MaterialType::kLambert;
    case 3:
    case 8:
      if (is_zero(p.ks)) return MaterialType::kLambert;
      return p.ns >= kMirrorShininess ? MaterialType::kMirror : MaterialType::kGlossy;
    case 4:
    case 6:
    case 7:
    case 9:
      return MaterialType::kDielectric;
    case 5:
      return MaterialType::kMirror;
    default:  // 2 and everything else: diffuse plus an optional highlight
      return is_zero(p.ks) ? MaterialType::kLambert : MaterialType::kPrincipled;
  }
}

}  // namespace

float roughness_from_shininess(float ns) {
  float alpha = std::sqrt(2.0f / (std::max(ns, 0.0f) + 2.0f));
  return std::clamp(alpha, kMinRoughness, 1.0f);
}

Material material_from_mtl(const MtlParams& p) {
  Material m;
  m.name = p.name;
  m.type = type_for_illum(p);
  m.base_color = p.kd;
  m.specular_color = p.ks;
  m.emission = p.ke;
  m.ior = p.ni > 1.0f ? p.ni : kDefaultDielectricIor;
  m.transmittance = is_zero(p.tf) ? Color(1.0f) : p.tf;
  if (m.type == MaterialType::kMirror && is_zero(m.specular_color)) m.specular_color = Color(1.0f);

  // Anisotropy as in the Disney BRDF: the aspect ratio stretches alpha along the tangent.
  float alpha = roughness_from_shininess(p.ns);
  float aspect = std::sqrt(1.0f - 0.9f * std::clamp(p.aniso, 0.0f, 1.0f));
  m.roughness_u = std::clamp(alpha / aspect, kMinRoughness, 1.0f);
  m.roughness_v = std::clamp(alpha * aspect, kMinRoughness, 1.0f);
  return m;
}

}  // namespace tuneray
