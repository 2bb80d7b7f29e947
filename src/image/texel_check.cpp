#include "image/texel_check.h"

#include <cmath>
#include <sstream>

namespace tuneray {

std::optional<BadTexel> find_bad_texel(const Image& image) {
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const Color& c = image.at(x, y);
      for (int channel = 0; channel < 3; ++channel) {
        const float v = c[channel];
        if (!std::isfinite(v) || v < 0.0f) return BadTexel{x, y, channel, v};
      }
    }
  }
  return std::nullopt;
}

std::string describe_bad_texel(const BadTexel& bad) {
  std::ostringstream out;
  out << "texel (" << bad.x << ", " << bad.y << ") has "
      << "rgb"[bad.channel] << " = " << bad.value
      << "; every texel must be finite and non-negative";
  return out.str();
}

}  // namespace tuneray
