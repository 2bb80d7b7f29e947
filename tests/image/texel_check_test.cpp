#include "image/texel_check.h"

#include <gtest/gtest.h>

#include <limits>

namespace tuneray {
namespace {

TEST(TexelCheck, FiniteNonNegativeImageHasNoBadTexel) {
  Image image(3, 2, Color(0.5f));
  image.at(2, 1) = Color(0.0f, 1e30f, 2.0f);
  EXPECT_FALSE(find_bad_texel(image).has_value());
}

TEST(TexelCheck, FindsTheFirstBadTexelRowByRow) {
  Image image(4, 3, Color(1.0f));
  image.at(3, 2) = Color(std::numeric_limits<float>::quiet_NaN());
  image.at(1, 1) = Color(1.0f, 1.0f, -0.25f);
  auto bad = find_bad_texel(image);
  ASSERT_TRUE(bad.has_value());
  EXPECT_EQ(bad->x, 1);
  EXPECT_EQ(bad->y, 1);
  EXPECT_EQ(bad->channel, 2);
  EXPECT_EQ(bad->value, -0.25f);
  EXPECT_EQ(describe_bad_texel(*bad),
            "texel (1, 1) has b = -0.25; every texel must be finite and non-negative");
}

TEST(TexelCheck, InfinityIsBad) {
  Image image(1, 1, Color(0.0f, std::numeric_limits<float>::infinity(), 0.0f));
  auto bad = find_bad_texel(image);
  ASSERT_TRUE(bad.has_value());
  EXPECT_EQ(bad->channel, 1);
}

}  // namespace
}  // namespace tuneray
