// Every failure names the file and says what is wrong.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/temp_dir.h"
#include "image/io.h"

namespace tuneray {
namespace {

#define EXPECT_IMAGE_ERROR(statement, path, problem)                               \
  try {                                                                            \
    statement;                                                                     \
    ADD_FAILURE() << "no ImageError from " #statement;                             \
  } catch (const ImageError& e) {                                                  \
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();    \
    EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what(); \
  }

TEST(ImageErrors, MissingFile) {
  testing::TempDir dir;
  const std::string path = dir.file("absent.exr");
  EXPECT_IMAGE_ERROR(read_image(path), path, "not found");
}

TEST(ImageErrors, UnknownExtension) {
  testing::TempDir dir;
  const std::string path = dir.write_bytes("picture.gif", "GIF89a");
  EXPECT_IMAGE_ERROR(read_image(path), path, "unknown image extension '.gif'");
  EXPECT_IMAGE_ERROR(write_image(dir.file("out.jpg"), Image(1, 1)), "out.jpg", "cannot write");
}

TEST(ImageErrors, TruncatedPfm) {
  testing::TempDir dir;
  const std::string path = dir.write_bytes("short.pfm", "PF\n2 2\n-1\n" + std::string(10, '\0'));
  EXPECT_IMAGE_ERROR(read_image(path), path,
                     "truncated PFM pixel data (expected 48 bytes, found 10)");
  const std::string header_only = dir.write_bytes("header.pfm", "PF\n2 2");
  EXPECT_IMAGE_ERROR(read_image(header_only), header_only, "truncated PFM header");
  const std::string not_pfm = dir.write_bytes("text.pfm", "P6\n2 2\n255\n");
  EXPECT_IMAGE_ERROR(read_image(not_pfm), not_pfm, "not a PFM file");
}

TEST(ImageErrors, InsaneDimensions) {
  testing::TempDir dir;
  const std::string huge = dir.write_bytes("huge.pfm", "PF\n40000 1\n-1\n");
  EXPECT_IMAGE_ERROR(read_image(huge), huge, "unsupported image size 40000x1");
  const std::string zero = dir.write_bytes("zero.pfm", "PF\n0 5\n-1\n");
  EXPECT_IMAGE_ERROR(read_image(zero), zero, "unsupported image size 0x5");
  EXPECT_IMAGE_ERROR(write_image(dir.file("empty.pfm"), Image()), "empty.pfm",
                     "unsupported image size 0x0");
}

TEST(ImageErrors, CorruptPng) {
  testing::TempDir dir;
  const std::string path =
      dir.write_bytes("broken.png", std::string("\x89PNG\r\n\x1a\n", 8) + "this is not a png");
  EXPECT_IMAGE_ERROR(read_image(path), path, "cannot decode image");
}

TEST(ImageErrors, CorruptExrAndHdr) {
  testing::TempDir dir;
  const std::string exr = dir.write_bytes("broken.exr", "v/1\x01 garbage garbage garbage");
  EXPECT_IMAGE_ERROR(read_image(exr), exr, "cannot read EXR");
  const std::string hdr = dir.write_bytes("fake.hdr", "P6\n1 1\n255\nabc");
  EXPECT_IMAGE_ERROR(read_image(hdr), hdr, "not a Radiance HDR file");
}

TEST(ImageErrors, TruncatedExrAndPng) {
  testing::TempDir dir;
  Image image(64, 64);
  for (int i = 0; i < 64 * 64; ++i)
    image.data()[i] = Color(i * 0.37f, i % 7 * 0.1f, 1.0f / (i + 1));
  for (const char* name : {"cut.exr", "cut.png"}) {
    const std::string path = dir.file(name);
    write_image(path, image);
    std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
    EXPECT_IMAGE_ERROR(read_image(path), path, "cannot ");
  }
}

TEST(ImageErrors, UnwritableDirectory) {
  testing::TempDir dir;
  for (const char* name : {"no/such/dir/out.png", "no/such/dir/out.exr", "no/such/dir/out.pfm"}) {
    const std::string path = dir.file(name);
    EXPECT_IMAGE_ERROR(write_image(path, Image(1, 1)), path, "writ");
  }
}

}  // namespace
}  // namespace tuneray
