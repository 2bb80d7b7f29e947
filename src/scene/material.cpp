#include "scene/material.h"

namespace tuneray {

const char* to_string(MaterialType type) {
  switch (type) {
    case MaterialType::kLambert:
      return "lambert";
    case MaterialType::kMirror:
      return "mirror";
    case MaterialType::kDielectric:
      return "dielectric";
    case MaterialType::kGlossy:
      return "glossy";
    case MaterialType::kPrincipled:
      return "principled";
  }
  return "unknown";
}

std::optional<MaterialType> material_type_from_string(std::string_view name) {
  for (MaterialType t : {MaterialType::kLambert, MaterialType::kMirror, MaterialType::kDielectric,
                         MaterialType::kGlossy, MaterialType::kPrincipled})
    if (name == to_string(t)) return t;
  return std::nullopt;
}

}  // namespace tuneray
