#include "image/io.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "image/atomic_file.h"
#include "image/formats.h"

namespace tuneray {

namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

namespace detail {

void check_dimensions(const std::string& path, long long width, long long height) {
  if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide) {
    throw ImageError(path + ": unsupported image size " + std::to_string(width) + "x" +
                     std::to_string(height) + " (each side must be 1.." +
                     std::to_string(kMaxImageSide) + ")");
  }
}

}  // namespace detail

ImageFormat image_format_from_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tga" || ext == ".bmp") {
    return ImageFormat::kLdr;
  }
  if (ext == ".hdr") return ImageFormat::kHdr;
  if (ext == ".exr") return ImageFormat::kExr;
  if (ext == ".pfm") return ImageFormat::kPfm;
  return ImageFormat::kUnknown;
}

Image read_image(const std::string& path, const ReadOptions& options) {
  const ImageFormat format = image_format_from_path(path);
  if (format == ImageFormat::kUnknown) {
    throw ImageError(path + ": unknown image extension '" + lower_extension(path) +
                     "' (readable: .png .jpg .jpeg .tga .bmp .hdr .exr .pfm)");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw ImageError(path + ": file not found");
  }
  switch (format) {
    case ImageFormat::kLdr:
      return detail::read_ldr(path, options.srgb_to_linear);
    case ImageFormat::kHdr:
      return detail::read_radiance_hdr(path);
    case ImageFormat::kExr:
      return detail::read_exr(path);
    case ImageFormat::kPfm:
    default:
      return detail::read_pfm(path);
  }
}

void write_image(const std::string& path, const Image& image, const WriteOptions& options) {
  detail::check_dimensions(path, image.width(), image.height());
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".exr" && ext != ".pfm")
    throw ImageError(path + ": cannot write images with extension '" + ext +
                     "' (writable: .png .exr .pfm)");
  replace_file(path, [&](const std::string& temporary) {
    try {
      if (ext == ".png")
        detail::write_png(temporary, image, options);
      else if (ext == ".exr")
        detail::write_exr(temporary, image);
      else
        detail::write_pfm(temporary, image);
    } catch (const ImageError& e) {
      // The writers name the file they were given: name the one the user asked for.
      std::string message = e.what();
      for (size_t at = message.find(temporary); at != std::string::npos;
           at = message.find(temporary, at + path.size()))
        message.replace(at, temporary.size(), path);
      throw ImageError(message);
    }
  });
}

}  // namespace tuneray
