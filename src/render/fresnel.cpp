#include <algorithm>
#include <cmath>

#include "render/bsdf.h"

namespace tuneray {

float fresnel_dielectric(float cos_i, float ior) {
  cos_i = std::clamp(cos_i, -1.0f, 1.0f);
  // A broken index (<= 0, NaN, inf) behaves as no interface rather than producing NaNs.
  float eta = ior > 0 && std::isfinite(ior) ? ior : 1.0f;
  if (cos_i < 0) {  // leaving the medium: the roles of the two indices swap
    eta = 1.0f / eta;
    cos_i = -cos_i;
  }
  float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;  // total internal reflection
  float cos_t = std::sqrt(1.0f - sin2_t);
  float r_parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  float r_perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parallel * r_parallel + r_perpendicular * r_perpendicular);
}

}  // namespace tuneray
