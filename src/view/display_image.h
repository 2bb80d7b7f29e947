// Writing what the viewer shows: 8-bit sRGB pixels, rows top to bottom, to any image format
// tuneray writes (src/image/io.h, through the atomic writer).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"

namespace tuneray {

// The display bytes as linear colours: a PNG written from them (clamped, no exposure) holds
// the same bytes again, since the sRGB curve is applied exactly both ways.
Image display_to_linear(const std::vector<uint8_t>& rgb, int width, int height);

// Writes the display bytes to `path` (.png, .exr or .pfm).
void write_display_image(const std::string& path, const std::vector<uint8_t>& rgb, int width,
                         int height);

}  // namespace tuneray
