// The EXR header check: our own files pass, and headers that promise more than the file holds
// (huge attributes, data windows whose chunk table cannot fit) are refused before OpenEXR
// allocates for them.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/temp_dir.h"
#include "image/exr_check.h"
#include "image/io.h"

namespace tuneray {
namespace {

std::string u32(uint32_t v) {
  std::string s(4, '\0');
  for (int k = 0; k < 4; ++k) s[k] = static_cast<char>((v >> (8 * k)) & 0xff);
  return s;
}

std::string attribute(const std::string& name, const std::string& type, const std::string& value,
                      uint32_t declared_size) {
  return name + '\0' + type + '\0' + u32(declared_size) + value;
}

// A scanline header: magic, version 2, a data window of width x height, a compression, the end.
std::string header(int32_t width, int32_t height, uint8_t compression = 0) {
  std::string window = u32(0) + u32(0) + u32(static_cast<uint32_t>(width - 1)) +
                       u32(static_cast<uint32_t>(height - 1));
  return u32(20000630u) + u32(2) + attribute("dataWindow", "box2i", window, 16) +
         attribute("compression", "compression", std::string(1, static_cast<char>(compression)),
                   1) +
         std::string(1, '\0');
}

void expect_refused(const std::string& path, const std::string& words) {
  try {
    detail::check_exr_header(path);
    FAIL() << "accepted " << path;
  } catch (const ImageError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("cannot read EXR"), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

TEST(ExrCheck, OurOwnFilesPass) {
  testing::TempDir dir;
  Image image(37, 21, Color(0.5f, 1.0f, 2.0f));
  const std::string path = dir.file("ours.exr");
  write_image(path, image);
  EXPECT_NO_THROW(detail::check_exr_header(path));
  EXPECT_EQ(read_image(path).width(), 37);
}

TEST(ExrCheck, ATruncatedFileIsRefusedByItsChunkTable) {
  testing::TempDir dir;
  Image image(64, 64, Color(0.25f));
  const std::string whole = dir.file("whole.exr");
  write_image(whole, image);
  std::string bytes(std::filesystem::file_size(whole), '\0');
  {
    std::ifstream in(whole, std::ios::binary);
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  const std::string cut = dir.write_bytes("cut.exr", bytes.substr(0, bytes.size() / 4));
  EXPECT_THROW(read_image(cut), ImageError);
}

TEST(ExrCheck, AHugeDataWindowInAFewBytesIsRefused) {
  testing::TempDir dir;
  // 2^30 lines would be 2^30 offsets (8 GiB) for OpenEXR to allocate.
  const std::string path = dir.write_bytes("tall.exr", header(4, 1 << 30) + std::string(64, 'x'));
  // Refused by the image size limit, before any chunk table is thought of.
  try {
    detail::check_exr_header(path);
    FAIL() << "accepted " << path;
  } catch (const ImageError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  const std::string tall = dir.write_bytes("tall2.exr", header(4, 4000) + std::string(64, 'x'));
  expect_refused(tall, "promises 4000 chunks");
}

TEST(ExrCheck, AnAttributeLargerThanTheFileIsRefused) {
  testing::TempDir dir;
  std::string bytes = u32(20000630u) + u32(2) + attribute("comments", "string", "hello", 1u << 30) +
                      std::string(8, '\0');
  expect_refused(dir.write_bytes("big.exr", bytes), "attribute 'comments' says it has");
}

TEST(ExrCheck, WrongMagicVersionAndMissingAttributesAreRefused) {
  testing::TempDir dir;
  expect_refused(dir.write_bytes("magic.exr", "v/1\x02" + u32(2) + std::string(40, '\0')),
                 "magic number");
  expect_refused(dir.write_bytes("version.exr", u32(20000630u) + u32(3) + std::string(40, '\0')),
                 "version 3");
  expect_refused(dir.write_bytes("empty.exr", u32(20000630u) + u32(2) + std::string(40, '\0')),
                 "no dataWindow");
  expect_refused(dir.write_bytes("short.exr", u32(20000630u)), "ends early");
  std::string unknown = header(4, 4, 42) + std::string(256, '\0');
  expect_refused(dir.write_bytes("codec.exr", unknown), "compression 42 is unknown");
  std::string long_name = u32(20000630u) + u32(2) + std::string(40, 'n') + std::string(64, '\0');
  expect_refused(dir.write_bytes("name.exr", long_name), "longer than the format allows");
}

}  // namespace
}  // namespace tuneray
