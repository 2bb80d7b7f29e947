#include <ImfRgbaFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "common/temp_dir.h"
#include "image/io.h"

namespace tuneray {
namespace {

TEST(Exr, FloatRoundTripIsBitExact) {
  testing::TempDir dir;
  Image image(3, 2);
  image.at(0, 0) = Color(0.1f, -2.5f, 1e-30f);
  image.at(2, 0) = Color(1e20f, 3.0f, 0.333333f);  // far outside the half range
  image.at(1, 1) = Color(std::numeric_limits<float>::quiet_NaN(), INFINITY, 7.0f);
  const std::string path = dir.file("round.exr");
  write_image(path, image);
  const Image back = read_image(path);
  ASSERT_EQ(back.width(), 3);
  ASSERT_EQ(back.height(), 2);
  EXPECT_EQ(std::memcmp(back.data(), image.data(), sizeof(Color) * 6), 0);
}

TEST(Exr, ReadsHalfRgbaFileFromOtherWriters) {
  testing::TempDir dir;
  const std::string path = dir.file("half.exr");
  {
    Imf::Rgba pixels[2] = {Imf::Rgba(0.5f, 0.25f, 2.0f, 1.0f), Imf::Rgba(-1.0f, 8.0f, 0.0f, 0.0f)};
    Imf::RgbaOutputFile file(path.c_str(), 2, 1, Imf::WRITE_RGBA);
    file.setFrameBuffer(pixels, 1, 2);
    file.writePixels(1);
  }
  const Image image = read_image(path);
  ASSERT_EQ(image.width(), 2);
  ASSERT_EQ(image.height(), 1);
  EXPECT_EQ(image.at(0, 0), Color(0.5f, 0.25f, 2.0f));
  EXPECT_EQ(image.at(1, 0), Color(-1.0f, 8.0f, 0.0f));
}

}  // namespace
}  // namespace tuneray
