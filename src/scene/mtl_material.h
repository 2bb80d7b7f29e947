// How Wavefront MTL parameters become our Material (documented in docs/materials.md).
#pragma once

#include <string>

#include "scene/material.h"

namespace tuneray {

// The MTL statements we use, with tinyobjloader's defaults for absent ones.
struct MtlParams {
  std::string name;
  Color kd{0.0f};         // Kd
  Color ks{0.0f};         // Ks
  Color ke{0.0f};         // Ke
  Color tf{0.0f};         // Tf (all zero = absent)
  float ns = 1.0f;        // Ns (Phong exponent)
  float ni = 1.0f;        // Ni
  float dissolve = 1.0f;  // d, or 1 - Tr
  int illum = 0;          // illumination model
  float aniso = 0.0f;     // PBR extension "aniso" in [0, 1]
};

// GGX alpha from a Phong exponent: alpha = sqrt(2 / (Ns + 2)) (Walter et al. 2007), clamped to
// [kMinRoughness, 1] so that Ns = 0 is fully rough and huge exponents stay numerically safe.
inline constexpr float kMinRoughness = 0.001f;
float roughness_from_shininess(float ns);

// Phong exponents at or above this become a perfect mirror under illum 3 and 8.
inline constexpr float kMirrorShininess = 1000.0f;

// The index of refraction used for dielectrics whose Ni is absent or not above 1.
inline constexpr float kDefaultDielectricIor = 1.5f;

Material material_from_mtl(const MtlParams& p);

}  // namespace tuneray
