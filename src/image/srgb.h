// The exact piecewise sRGB transfer curve (IEC 61966-2-1), not the 2.2 gamma approximation,
// so that 8-bit files decode to the same linear values every other tool computes.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace tuneray {

inline float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

inline float linear_to_srgb(float l) {
  return l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

// Linear value of each 8-bit sRGB code; decoding a texture is then one load per channel.
inline const std::array<float, 256>& srgb8_to_linear_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgb_to_linear(static_cast<float>(i) / 255.0f);
    return t;
  }();
  return table;
}

}  // namespace tuneray
