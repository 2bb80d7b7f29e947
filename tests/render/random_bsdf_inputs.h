// Random inputs for the BSDF tests that compare two implementations on the same draws.
#pragma once

#include <algorithm>
#include <cmath>

#include "math/rng.h"
#include "math/vec.h"

namespace tuneray::testing {

// Uniform on the unit sphere.
inline Vec3f random_direction(Pcg32& rng) {
  const float z = 1.0f - 2.0f * rng.next_float();
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * rng.next_float();
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Black with probability `zero_chance` (the BSDFs' special case), else uniform in [0, 1)^3.
inline Color random_color(Pcg32& rng, float zero_chance) {
  if (rng.next_float() < zero_chance) return Color(0.0f);
  return Color(rng.next_float(), rng.next_float(), rng.next_float());
}

}  // namespace tuneray::testing
