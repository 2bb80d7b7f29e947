#include <gtest/gtest.h>
#include <stb_image_write.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "common/temp_dir.h"
#include "image/io.h"
#include "image/srgb.h"

namespace tuneray {
namespace {

float byte_value(int b) {
  return b / 255.0f;
}

// Reads back the stored 8-bit codes of a PNG we wrote.
Image read_codes(const std::string& path) {
  return read_image(path, {.srgb_to_linear = false});
}

TEST(Png, WritesKnownSrgbCodes) {
  testing::TempDir dir;
  Image image(4, 2);
  image.at(0, 0) = Color(0.5f, 0.0f, 1.0f);
  image.at(1, 0) = Color(std::numeric_limits<float>::quiet_NaN(), INFINITY, -3.0f);
  image.at(2, 0) = Color(7.0f, 0.0031308f * 0.5f, 0.05f);
  const std::string path = dir.file("codes.png");
  write_image(path, image);
  const Image codes = read_codes(path);
  EXPECT_EQ(codes.at(0, 0), Color(byte_value(188), 0.0f, 1.0f));
  EXPECT_EQ(codes.at(1, 0), Color(0.0f));  // NaN, inf and negative become black
  // 7 clamps to white; 0.0015654 * 12.92 * 255 = 5.16; linear 0.05 is sRGB 0.24781 = 63.19.
  EXPECT_EQ(codes.at(2, 0), Color(1.0f, byte_value(5), byte_value(63)));
}

TEST(Png, ExposureAndFilmicCurve) {
  testing::TempDir dir;
  const Image image(1, 1, Color(0.25f, 1.0f, 0.0f));
  const std::string path = dir.file("exposed.png");
  write_image(path, image, {.exposure = 1.0f});
  EXPECT_EQ(read_codes(path).at(0, 0), Color(byte_value(188), 1.0f, 0.0f));

  // ACES fit at 1: 2.54 / 3.16 = 0.80380 -> sRGB 0.90823 -> 231.6 -> 232.
  write_image(path, Image(1, 1, Color(1.0f)), {.tonemap = true});
  EXPECT_EQ(read_codes(path).at(0, 0), Color(byte_value(232)));
}

TEST(Png, RoundTripWithinHalfACode) {
  testing::TempDir dir;
  Image image(16, 3);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 16; ++x)
      image.at(x, y) = Color(x / 15.0f, std::pow(x / 15.0f, 3.0f), y / 2.0f);
  }
  const std::string path = dir.file("round.png");
  write_image(path, image);
  const Image back = read_image(path);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 16; ++x) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(linear_to_srgb(back.at(x, y)[k]), linear_to_srgb(image.at(x, y)[k]),
                    0.5f / 255.0f + 1e-5f)
            << x << "," << y << "," << k;
      }
    }
  }
}

// A 16-bit PNG built by hand (stb_image_write only writes 8 bits): zlib with one stored block.
std::string be32(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
          static_cast<char>(v)};
}

std::uint32_t crc32(const std::string& s) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char c : s) {
    crc ^= c;
    for (int i = 0; i < 8; ++i) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string chunk(const std::string& type, const std::string& data) {
  return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(crc32(type + data));
}

std::string png16_rgb(int width, int height, const std::vector<std::uint16_t>& samples) {
  std::string raw;
  for (int y = 0; y < height; ++y) {
    raw += '\0';  // filter: none
    for (int i = 0; i < width * 3; ++i) {
      const std::uint16_t s = samples[static_cast<size_t>(y) * width * 3 + i];
      raw += static_cast<char>(s >> 8);
      raw += static_cast<char>(s & 0xFF);
    }
  }
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  const auto len = static_cast<std::uint16_t>(raw.size());
  std::string zlib = "\x78\x01\x01";
  zlib += {static_cast<char>(len & 0xFF), static_cast<char>(len >> 8),
           static_cast<char>(~len & 0xFF), static_cast<char>((~len >> 8) & 0xFF)};
  zlib += raw + be32((b << 16) | a);
  const std::string ihdr = be32(width) + be32(height) + std::string("\x10\x02\x00\x00\x00", 5);
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", zlib) +
         chunk("IEND", "");
}

TEST(Png, Reads16BitFiles) {
  testing::TempDir dir;
  const std::string path =
      dir.write_bytes("deep.png", png16_rgb(2, 1, {0, 65535, 32768, 1000, 2000, 3000}));
  const Image codes = read_codes(path);
  ASSERT_EQ(codes.width(), 2);
  EXPECT_EQ(codes.at(0, 0), Color(0.0f, 1.0f, 32768 / 65535.0f));
  EXPECT_EQ(codes.at(1, 0), Color(1000 / 65535.0f, 2000 / 65535.0f, 3000 / 65535.0f));
  const Image linear = read_image(path);
  EXPECT_FLOAT_EQ(linear.at(0, 0).z, srgb_to_linear(32768 / 65535.0f));
}

TEST(Hdr, ReadsRadianceFileTopRowFirst) {
  testing::TempDir dir;
  const std::string path = dir.file("sky.hdr");
  // Powers of two share an exponent exactly in RGBE, so the values survive unchanged.
  const float pixels[6] = {1.0f, 0.5f, 0.25f, 4.0f, 2.0f, 8.0f};
  ASSERT_TRUE(stbi_write_hdr(path.c_str(), 1, 2, 3, pixels));
  const Image image = read_image(path);
  ASSERT_EQ(image.width(), 1);
  ASSERT_EQ(image.height(), 2);
  EXPECT_EQ(image.at(0, 0), Color(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(image.at(0, 1), Color(4.0f, 2.0f, 8.0f));
}

}  // namespace
}  // namespace tuneray
