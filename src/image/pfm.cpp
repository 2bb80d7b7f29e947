// Portable float map: "PF" (RGB) or "Pf" (grey), width height, scale whose sign gives the byte
// order (negative = little endian) and whose magnitude scales the values, then rows of 32-bit
// floats from the bottom of the image to the top.
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "image/formats.h"

namespace tuneray::detail {

namespace {

class PfmHeaderParser {
 public:
  PfmHeaderParser(const std::string& path, const std::vector<char>& bytes)
      : path_(path), bytes_(bytes) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw ImageError(path_ + ": " + problem);
  }

  std::string token() {
    while (pos_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[pos_]))) ++pos_;
    const size_t start = pos_;
    while (pos_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[pos_])) &&
           pos_ - start < 64) {
      ++pos_;
    }
    if (pos_ == start) fail("truncated PFM header");
    return std::string(bytes_.data() + start, pos_ - start);
  }

  long long integer() {
    const std::string t = token();
    long long value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec != std::errc() || end != t.data() + t.size()) fail("bad PFM header field '" + t + "'");
    return value;
  }

  float real() {
    const std::string t = token();
    float value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec != std::errc() || end != t.data() + t.size()) fail("bad PFM scale '" + t + "'");
    return value;
  }

  // Exactly one whitespace character separates the header from the pixel data.
  size_t data_offset() {
    if (pos_ >= bytes_.size() || !std::isspace(static_cast<unsigned char>(bytes_[pos_]))) {
      fail("truncated PFM header");
    }
    return pos_ + 1;
  }

 private:
  const std::string& path_;
  const std::vector<char>& bytes_;
  size_t pos_ = 2;  // after the magic
};

float load_float(const char* p, bool swap) {
  std::uint32_t bits;
  std::memcpy(&bits, p, 4);
  if (swap) bits = __builtin_bswap32(bits);
  return std::bit_cast<float>(bits);
}

}  // namespace

Image read_pfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ImageError(path + ": cannot open file");
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
  PfmHeaderParser parser(path, bytes);
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != 'F' && bytes[1] != 'f')) {
    parser.fail("not a PFM file (expected 'PF' or 'Pf')");
  }
  const int channels = bytes[1] == 'F' ? 3 : 1;
  const long long width = parser.integer();
  const long long height = parser.integer();
  check_dimensions(path, width, height);
  const float scale = parser.real();
  if (!std::isfinite(scale) || scale == 0.0f) parser.fail("invalid PFM scale (must be non-zero)");
  const size_t offset = parser.data_offset();

  const size_t row_bytes = static_cast<size_t>(width) * channels * 4;
  const size_t needed = row_bytes * static_cast<size_t>(height);
  if (bytes.size() - offset < needed) {
    throw ImageError(path + ": truncated PFM pixel data (expected " + std::to_string(needed) +
                     " bytes, found " + std::to_string(bytes.size() - offset) + ")");
  }
  const bool little = scale < 0;
  const bool swap = little != (std::endian::native == std::endian::little);
  const float factor = std::abs(scale);

  Image image(static_cast<int>(width), static_cast<int>(height));
  for (int y = 0; y < image.height(); ++y) {
    const char* row = bytes.data() + offset + row_bytes * (image.height() - 1 - y);
    for (int x = 0; x < image.width(); ++x) {
      Color& c = image.at(x, y);
      for (int k = 0; k < 3; ++k) {
        const int channel = channels == 3 ? k : 0;
        c[k] = load_float(row + (static_cast<size_t>(x) * channels + channel) * 4, swap);
      }
      if (factor != 1.0f) c *= factor;
    }
  }
  return image;
}

void write_pfm(const std::string& path, const Image& image) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw ImageError(path + ": cannot open for writing");
  const bool little = std::endian::native == std::endian::little;
  out << "PF\n" << image.width() << ' ' << image.height() << '\n' << (little ? "-1\n" : "1\n");
  for (int y = image.height() - 1; y >= 0; --y) {
    out.write(reinterpret_cast<const char*>(&image.at(0, y)),
              static_cast<std::streamsize>(sizeof(Color)) * image.width());
  }
  out.close();
  if (!out) throw ImageError(path + ": write failed");
}

}  // namespace tuneray::detail
