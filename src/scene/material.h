// Materials as one flat record (no virtual dispatch): the integrator switches on the type, and
// the equal-time work can evaluate shared parts of lobes without branches.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "math/vec.h"

namespace tuneray {

inline constexpr int32_t kNoTexture = -1;

enum class MaterialType : uint8_t {
  kLambert,     // base_color / pi
  kMirror,      // perfect specular reflection tinted by specular_color
  kDielectric,  // smooth glass: Fresnel reflection + refraction with ior, tinted by transmittance
  kGlossy,      // anisotropic GGX conductor, Schlick Fresnel from specular_color (F0)
  kPrincipled,  // MTL: Lambert base (base_color) + GGX specular coat (specular_color as F0)
};

const char* to_string(MaterialType type);
// Inverse of to_string; nullopt for an unknown name.
std::optional<MaterialType> material_type_from_string(std::string_view name);

struct Material {
  std::string name;
  MaterialType type = MaterialType::kLambert;
  Color base_color{0.8f};             // diffuse albedo (Kd)
  int32_t base_texture = kNoTexture;  // multiplies base_color (map_Kd), index into Scene::textures
  Color specular_color{0.0f};         // F0 for glossy/principled, tint for mirror (Ks)
  Color transmittance{1.0f};          // dielectric tint (Tf)
  Color emission{0.0f};               // radiance emitted by the front side (Ke); > 0 makes a light
  float roughness_u = 0.5f;           // GGX alpha along the shading tangent
  float roughness_v = 0.5f;           // GGX alpha along the bitangent
  float ior = 1.5f;                   // index of refraction (Ni)
  bool two_sided_emission = false;

  bool is_emissive() const { return max_component(emission) > 0.0f; }
  // True when the BSDF is a Dirac delta (no light sampling possible).
  bool is_specular() const {
    return type == MaterialType::kMirror || type == MaterialType::kDielectric;
  }
};

}  // namespace tuneray
