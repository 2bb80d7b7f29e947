// Formats decoded by stb_image (PNG, JPEG, TGA, BMP, Radiance HDR) and PNG output through
// stb_image_write. stb's global vertical-flip switches are never touched: other code may share
// the library.
#include <stb_image.h>
#include <stb_image_write.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "image/formats.h"
#include "image/srgb.h"
#include "image/tonemap.h"

namespace tuneray::detail {

namespace {

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

std::string stb_reason() {
  const char* reason = stbi_failure_reason();
  return reason ? reason : "unknown error";
}

// Checks the header before decoding so that a corrupt size never becomes an allocation.
void check_header(const std::string& path) {
  int width = 0, height = 0, components = 0;
  if (!stbi_info(path.c_str(), &width, &height, &components)) {
    throw ImageError(path + ": cannot decode image (" + stb_reason() + ")");
  }
  check_dimensions(path, width, height);
}

}  // namespace

Image read_ldr(const std::string& path, bool srgb_to_linear_values) {
  check_header(path);
  int width = 0, height = 0, components = 0;
  if (stbi_is_16_bit(path.c_str())) {
    std::unique_ptr<stbi_us, StbFree> pixels(
        stbi_load_16(path.c_str(), &width, &height, &components, 3));
    if (!pixels) throw ImageError(path + ": cannot decode image (" + stb_reason() + ")");
    Image image(width, height);
    for (size_t i = 0; i < image.pixel_count(); ++i) {
      for (int k = 0; k < 3; ++k) {
        const float v = pixels.get()[i * 3 + k] / 65535.0f;
        image.data()[i][k] = srgb_to_linear_values ? srgb_to_linear(v) : v;
      }
    }
    return image;
  }
  std::unique_ptr<stbi_uc, StbFree> pixels(
      stbi_load(path.c_str(), &width, &height, &components, 3));
  if (!pixels) throw ImageError(path + ": cannot decode image (" + stb_reason() + ")");
  const auto& table = srgb8_to_linear_table();
  Image image(width, height);
  for (size_t i = 0; i < image.pixel_count(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const stbi_uc v = pixels.get()[i * 3 + k];
      image.data()[i][k] = srgb_to_linear_values ? table[v] : v / 255.0f;
    }
  }
  return image;
}

Image read_radiance_hdr(const std::string& path) {
  // stbi_loadf would silently gamma-decode an 8-bit file; a .hdr must really be Radiance.
  if (!stbi_is_hdr(path.c_str())) throw ImageError(path + ": not a Radiance HDR file");
  check_header(path);
  int width = 0, height = 0, components = 0;
  std::unique_ptr<float, StbFree> pixels(stbi_loadf(path.c_str(), &width, &height, &components, 3));
  if (!pixels) throw ImageError(path + ": cannot decode HDR image (" + stb_reason() + ")");
  Image image(width, height);
  for (size_t i = 0; i < image.pixel_count(); ++i) {
    const float* p = pixels.get() + i * 3;
    image.data()[i] = Color(p[0], p[1], p[2]);
  }
  return image;
}

void write_png(const std::string& path, const Image& image, const WriteOptions& options) {
  const float exposure_scale = std::exp2(options.exposure);
  std::vector<std::uint8_t> bytes(image.pixel_count() * 3);
  for (size_t i = 0; i < image.pixel_count(); ++i) {
    for (int k = 0; k < 3; ++k) {
      bytes[i * 3 + k] = encode_display_byte(image.data()[i][k], exposure_scale, options.tonemap);
    }
  }
  if (!stbi_write_png(path.c_str(), image.width(), image.height(), 3, bytes.data(),
                      image.width() * 3)) {
    throw ImageError(path + ": cannot write PNG");
  }
}

}  // namespace tuneray::detail
