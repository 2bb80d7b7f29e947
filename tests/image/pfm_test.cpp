#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "common/temp_dir.h"
#include "image/io.h"

namespace tuneray {
namespace {

std::string float_bytes(float f, bool big_endian) {
  char b[4];
  std::memcpy(b, &f, 4);
  if (big_endian) std::swap(b[0], b[3]), std::swap(b[1], b[2]);
  return std::string(b, 4);
}

TEST(Pfm, RoundTripIsBitExact) {
  testing::TempDir dir;
  Image image(3, 2);
  image.at(0, 0) = Color(0.1f, -2.5f, 1e-30f);
  image.at(2, 0) = Color(1e20f, 3.0f, 0.333333f);
  image.at(1, 1) = Color(std::numeric_limits<float>::quiet_NaN(), INFINITY, 7.0f);
  const std::string path = dir.file("round.pfm");
  write_image(path, image);
  const Image back = read_image(path);
  ASSERT_EQ(back.width(), 3);
  ASSERT_EQ(back.height(), 2);
  EXPECT_EQ(std::memcmp(back.data(), image.data(), sizeof(Color) * 6), 0);
  EXPECT_TRUE(std::isnan(back.at(1, 1).x));
}

TEST(Pfm, ReadsBigEndianGreyscaleBottomRowFirst) {
  testing::TempDir dir;
  // Rows in the file: bottom (1, 2), then top (3, 4).
  std::string bytes = "Pf\n2 2\n1.0\n";
  for (float v : {1.0f, 2.0f, 3.0f, 4.0f}) bytes += float_bytes(v, true);
  const Image image = read_image(dir.write_bytes("grey.pfm", bytes));
  EXPECT_EQ(image.at(0, 0), Color(3.0f));
  EXPECT_EQ(image.at(1, 0), Color(4.0f));
  EXPECT_EQ(image.at(0, 1), Color(1.0f));
  EXPECT_EQ(image.at(1, 1), Color(2.0f));
}

TEST(Pfm, ScaleMagnitudeMultipliesValues) {
  testing::TempDir dir;
  const std::string bytes = "PF\n1 1\n-0.5\n" + float_bytes(4.0f, false) +
                            float_bytes(2.0f, false) + float_bytes(-6.0f, false);
  const Image image = read_image(dir.write_bytes("scaled.pfm", bytes));
  EXPECT_EQ(image.at(0, 0), Color(2.0f, 1.0f, -3.0f));
}

}  // namespace
}  // namespace tuneray
