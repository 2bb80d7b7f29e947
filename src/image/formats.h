// Internal: one reader/writer per file family, called by io.cpp after it has dispatched on the
// extension and checked that the file exists. Not part of the library's interface.
#pragma once

#include <string>

#include "image/image.h"
#include "image/io.h"

namespace tuneray::detail {

// Throws ImageError unless 0 < width, height <= kMaxImageSide.
void check_dimensions(const std::string& path, long long width, long long height);

Image read_ldr(const std::string& path, bool srgb_to_linear);
Image read_radiance_hdr(const std::string& path);
Image read_exr(const std::string& path);
Image read_pfm(const std::string& path);

void write_png(const std::string& path, const Image& image, const WriteOptions& options);
void write_exr(const std::string& path, const Image& image);
void write_pfm(const std::string& path, const Image& image);

}  // namespace tuneray::detail
