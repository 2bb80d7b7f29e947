// Mapping of linear radiance to 8-bit display values for PNG output.
#pragma once

#include <cstdint>

namespace tuneray {

// Narkowicz's fit of the ACES filmic curve: maps [0, inf) smoothly onto [0, 1).
float filmic_aces(float x);

// Scales by `exposure_scale`, then clamps (or applies the filmic curve), encodes with the sRGB
// curve and rounds to the nearest byte. Non-finite and negative values become 0 so that a
// single bad sample cannot produce a bright pixel.
std::uint8_t encode_display_byte(float linear, float exposure_scale, bool filmic);

}  // namespace tuneray
