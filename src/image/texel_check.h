// Radiance and reflectance images must hold finite, non-negative values: a NaN texel spreads
// NaN through every path that samples it (the film then drops those samples and the image
// comes out black without a word) and a negative one makes the environment's sampling
// distribution invalid.
#pragma once

#include <optional>
#include <string>

#include "image/image.h"

namespace tuneray {

struct BadTexel {
  int x = 0, y = 0;
  int channel = 0;  // 0 r, 1 g, 2 b
  float value = 0;
};

// The first texel (row by row) with a NaN, infinite or negative channel, if any.
std::optional<BadTexel> find_bad_texel(const Image& image);

// "texel (x, y) has g = nan; every texel must be finite and non-negative", for error messages.
std::string describe_bad_texel(const BadTexel& bad);

}  // namespace tuneray
