// Linear radiance to display bytes as fast as a 30 fps window needs: a frame of 640x360 has
// 700k channel values, and the exact sRGB curve costs a pow() each. The encoder finds, once per
// exposure, the 255 linear values where encode_display_byte (image/tonemap.h, what `render
// --out F.png` writes) steps to the next byte, and a table from a value's exponent and top
// mantissa bits to the byte at the start of its bucket; a value then costs a table load and at
// most a comparison or two with the steps: the same bytes, no pow().
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace tuneray {

class DisplayEncoder {
 public:
  // `exposure_scale`: 2^stops, > 0. Clamping display (no filmic curve).
  explicit DisplayEncoder(float exposure_scale);

  std::uint8_t encode(float linear) const;
  float exposure_scale() const { return scale_; }

 private:
  float scale_;
  // steps_[k]: the smallest linear value whose byte is k + 1.
  std::array<float, 255> steps_{};
  // Buckets of values with the same exponent and top kMantissaBits mantissa bits, from the
  // bucket of steps_[0] up to that of steps_[254]: narrower than the space between two steps,
  // so the bucket's first byte is at most one or two steps short.
  static constexpr int kMantissaBits = 10;
  std::uint32_t first_bucket_ = 0;
  std::vector<std::uint8_t> bucket_byte_;
};

}  // namespace tuneray
