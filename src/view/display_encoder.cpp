#include "view/display_encoder.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "image/tonemap.h"

namespace tuneray {

DisplayEncoder::DisplayEncoder(float exposure_scale) : scale_(exposure_scale) {
  // encode_display_byte is monotone in the linear value, so each step is found by bisecting
  // between a value below it and one above it down to adjacent floats.
  const float top = 1.0f / exposure_scale;
  for (int k = 1; k <= 255; ++k) {
    float below = 0.0f, above = top * 1.001f;
    while (std::nextafter(below, above) < above) {
      float mid = below + (above - below) * 0.5f;
      if (mid <= below || mid >= above) break;
      if (encode_display_byte(mid, exposure_scale, false) >= k)
        above = mid;
      else
        below = mid;
    }
    steps_[static_cast<size_t>(k - 1)] = above;
  }
  constexpr int shift = 23 - kMantissaBits;
  first_bucket_ = std::bit_cast<std::uint32_t>(steps_.front()) >> shift;
  const std::uint32_t last_bucket = std::bit_cast<std::uint32_t>(steps_.back()) >> shift;
  bucket_byte_.resize(last_bucket - first_bucket_ + 1);
  for (std::uint32_t b = first_bucket_; b <= last_bucket; ++b) {
    const float start = std::bit_cast<float>(b << shift);
    bucket_byte_[b - first_bucket_] = static_cast<std::uint8_t>(
        std::upper_bound(steps_.begin(), steps_.end(), start) - steps_.begin());
  }
}

std::uint8_t DisplayEncoder::encode(float linear) const {
  // Non-finite values (NaN, infinity, or an overflow of the exposure) show as 0, as in
  // encode_display_byte: a single bad sample must not show as a bright pixel.
  if (!(linear > 0.0f) || !std::isfinite(linear * scale_)) return 0;
  if (linear < steps_.front()) return 0;
  if (linear >= steps_.back()) return 255;
  const std::uint32_t bucket = (std::bit_cast<std::uint32_t>(linear) >> (23 - kMantissaBits));
  unsigned byte = bucket_byte_[bucket - first_bucket_];
  while (byte < 255 && linear >= steps_[byte]) ++byte;
  return static_cast<std::uint8_t>(byte);
}

}  // namespace tuneray
