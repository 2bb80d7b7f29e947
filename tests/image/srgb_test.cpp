#include "image/srgb.h"

#include <gtest/gtest.h>

namespace tuneray {
namespace {

TEST(Srgb, KnownValues) {
  EXPECT_NEAR(srgb_to_linear(0.5f), 0.2140411f, 1e-6f);
  EXPECT_NEAR(linear_to_srgb(0.5f), 0.7353570f, 1e-6f);
  // Linear segment below the knee.
  EXPECT_FLOAT_EQ(srgb_to_linear(0.04f), 0.04f / 12.92f);
  EXPECT_FLOAT_EQ(linear_to_srgb(0.003f), 0.003f * 12.92f);
  EXPECT_FLOAT_EQ(srgb_to_linear(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(linear_to_srgb(1.0f), 1.0f);
}

TEST(Srgb, CurvesAreInverse) {
  for (int i = 0; i <= 100; ++i) {
    const float s = i / 100.0f;
    EXPECT_NEAR(linear_to_srgb(srgb_to_linear(s)), s, 2e-6f) << s;
  }
}

TEST(Srgb, TableMatchesCurve) {
  const auto& table = srgb8_to_linear_table();
  EXPECT_EQ(table[0], 0.0f);
  EXPECT_FLOAT_EQ(table[255], 1.0f);
  EXPECT_NEAR(table[188], 0.5029f, 1e-4f);  // byte 188 is the nearest code to linear 0.5
  for (int i = 0; i < 256; ++i) EXPECT_FLOAT_EQ(table[i], srgb_to_linear(i / 255.0f));
}

}  // namespace
}  // namespace tuneray
