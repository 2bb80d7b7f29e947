#include "image/texture_lookup.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tuneray {
namespace {

// Displayed as    A B   (row 0, top,    v in [0.5, 1])
//                 C D   (row 1, bottom, v in [0, 0.5])
const Color A(1, 0, 0), B(0, 1, 0), C(0, 0, 1), D(1, 1, 1);

Image two_by_two() {
  Image img(2, 2);
  img.at(0, 0) = A;
  img.at(1, 0) = B;
  img.at(0, 1) = C;
  img.at(1, 1) = D;
  return img;
}

void expect_color_near(Color got, Color want) {
  EXPECT_NEAR(got.x, want.x, 1e-6f);
  EXPECT_NEAR(got.y, want.y, 1e-6f);
  EXPECT_NEAR(got.z, want.z, 1e-6f);
}

TEST(TextureLookup, NearestUsesBottomLeftOrigin) {
  const Image img = two_by_two();
  EXPECT_EQ(sample_nearest_wrap(img, {0.25f, 0.25f}), C);
  EXPECT_EQ(sample_nearest_wrap(img, {0.75f, 0.25f}), D);
  EXPECT_EQ(sample_nearest_wrap(img, {0.25f, 0.75f}), A);
  EXPECT_EQ(sample_nearest_wrap(img, {0.0f, 0.0f}), C);
  EXPECT_EQ(sample_nearest_wrap(img, {0.75f, 0.999f}), B);
  EXPECT_EQ(sample_nearest_wrap(img, {-0.25f, 1.75f}), B);  // repeats to (0.75, 0.75)
}

TEST(TextureLookup, BilinearAtTexelCentresIsExact) {
  const Image img = two_by_two();
  EXPECT_EQ(sample_bilinear_wrap(img, {0.25f, 0.75f}), A);
  EXPECT_EQ(sample_bilinear_wrap(img, {0.75f, 0.25f}), D);
}

TEST(TextureLookup, BilinearCentreIsAverage) {
  expect_color_near(sample_bilinear_wrap(two_by_two(), {0.5f, 0.5f}), (A + B + C + D) * 0.25f);
}

TEST(TextureLookup, BilinearWeights) {
  // A quarter texel right of A's centre: 3/4 A + 1/4 B.
  expect_color_near(sample_bilinear_wrap(two_by_two(), {0.375f, 0.75f}), A * 0.75f + B * 0.25f);
  // A quarter texel below A's centre: 3/4 A + 1/4 C.
  expect_color_near(sample_bilinear_wrap(two_by_two(), {0.25f, 0.625f}), A * 0.75f + C * 0.25f);
}

TEST(TextureLookup, BilinearWrapsAtEdges) {
  const Image img = two_by_two();
  // The left edge lies halfway between the first column and the last (wrapped) one.
  expect_color_near(sample_bilinear_wrap(img, {0.0f, 0.75f}), (A + B) * 0.5f);
  expect_color_near(sample_bilinear_wrap(img, {1.0f, 0.75f}), (A + B) * 0.5f);
  // The top edge mixes the top and bottom rows.
  expect_color_near(sample_bilinear_wrap(img, {0.25f, 1.0f}), (A + C) * 0.5f);
  expect_color_near(sample_bilinear_wrap(img, {0.0f, 0.0f}), (A + B + C + D) * 0.25f);
}

TEST(TextureLookup, BilinearRepeatsOutsideUnitSquare) {
  const Image img = two_by_two();
  for (Vec2f shift : {Vec2f(1, 0), Vec2f(-1, 0), Vec2f(0, -3), Vec2f(5, 7), Vec2f(-2, -2)}) {
    expect_color_near(sample_bilinear_wrap(img, Vec2f(0.375f, 0.625f) + shift),
                      sample_bilinear_wrap(img, {0.375f, 0.625f}));
  }
}

TEST(TextureLookup, BadInputGivesBlack) {
  EXPECT_EQ(sample_bilinear_wrap(two_by_two(), {NAN, 0.5f}), Color(0));
  EXPECT_EQ(sample_nearest_wrap(two_by_two(), {0.5f, INFINITY}), Color(0));
  EXPECT_EQ(sample_bilinear_wrap(Image(), {0.5f, 0.5f}), Color(0));
}

}  // namespace
}  // namespace tuneray
