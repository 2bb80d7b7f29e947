#include "image/tonemap.h"

#include <algorithm>
#include <cmath>

#include "image/srgb.h"

namespace tuneray {

float filmic_aces(float x) {
  constexpr float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  return std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f);
}

std::uint8_t encode_display_byte(float linear, float exposure_scale, bool filmic) {
  float v = linear * exposure_scale;
  if (!std::isfinite(v) || v <= 0.0f) return 0;
  v = filmic ? filmic_aces(v) : std::min(v, 1.0f);
  return static_cast<std::uint8_t>(std::lround(linear_to_srgb(v) * 255.0f));
}

}  // namespace tuneray
