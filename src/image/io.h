// Image files. Reading: PNG/JPG/TGA/BMP (8-bit, sRGB decoded to linear unless `linear`), HDR,
// EXR, PFM. Writing by extension: .png (tonemapped, sRGB, 8-bit), .pfm and .exr (linear float).
// NaN and infinite pixels are kept in float formats and written as 0 in PNG.
// Errors throw ImageError naming the file and the problem.
#pragma once

#include <stdexcept>
#include <string>

#include "image/image.h"

namespace tuneray {

class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ReadOptions {
  bool srgb_to_linear = true;  // only for 8-bit formats
};

// Larger sides are rejected as corrupt headers rather than attempted as huge allocations.
inline constexpr int kMaxImageSide = 32768;

// File kind, decided by the (case-insensitive) extension alone.
enum class ImageFormat {
  kUnknown,
  kLdr,  // .png .jpg .jpeg .tga .bmp: 8-bit (or 16-bit PNG) display-referred values
  kHdr,  // .hdr (Radiance RGBE), linear
  kExr,  // .exr, linear
  kPfm,  // .pfm, linear
};
ImageFormat image_format_from_path(const std::string& path);
inline bool is_linear_float_format(ImageFormat f) {
  return f == ImageFormat::kHdr || f == ImageFormat::kExr || f == ImageFormat::kPfm;
}

Image read_image(const std::string& path, const ReadOptions& options = {});

struct WriteOptions {
  float exposure = 0.0f;  // stops, applied before tonemapping (PNG only)
  bool tonemap = false;   // PNG: false = clamp, true = ACES-like filmic curve
};

void write_image(const std::string& path, const Image& image, const WriteOptions& options = {});

}  // namespace tuneray
