#include "image/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace tuneray {
namespace {

TEST(Metrics, ReferenceNoiseIsAQuarterOfTheHalvesSquaredDifference) {
  Image a(2, 1), b(2, 1);
  a.at(0, 0) = Color(0.5f, 0.5f, 0.5f);
  b.at(0, 0) = Color(0.5f, 0.5f, 0.3f);
  a.at(1, 0) = Color(0.0f, 0.2f, 0.0f);
  b.at(1, 0) = Color(0.0f, 0.0f, 0.0f);
  // Two differences of 0.2 over six values: mse 0.08 / 6, a quarter of it.
  EXPECT_NEAR(reference_noise_mse(a, b), 0.08 / 6 / 4, 1e-9);
  EXPECT_THROW(reference_noise_mse(a, Image(1, 1)), std::invalid_argument);
}

TEST(Metrics, RmseWithoutReferenceNoiseSubtractsInQuadrature) {
  EXPECT_DOUBLE_EQ(rmse_without_reference_noise(0.5, 0.09), 0.4);
  EXPECT_DOUBLE_EQ(rmse_without_reference_noise(0.5, 0.0), 0.5);
  // Measured below the reference's own noise (chance): nothing of ours is left, not a NaN.
  EXPECT_EQ(rmse_without_reference_noise(0.1, 0.02), 0.0);
  EXPECT_THROW(rmse_without_reference_noise(-0.1, 0.0), std::invalid_argument);
  EXPECT_THROW(rmse_without_reference_noise(0.1, std::nan("")), std::invalid_argument);
  EXPECT_THROW(rmse_without_reference_noise(INFINITY, 0.0), std::invalid_argument);
}

TEST(Metrics, OneChannelOffCountsChannelsSeparately) {
  const ErrorMetrics m = compare_images(Image(1, 1, Color(1, 0, 0)), Image(1, 1, Color(0)));
  EXPECT_DOUBLE_EQ(m.mse, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(m.rmse, std::sqrt(1.0 / 3.0));
  EXPECT_DOUBLE_EQ(m.psnr, 10.0 * std::log10(3.0));
  EXPECT_DOUBLE_EQ(m.relmse, (1.0 / 0.01) / 3.0);
  EXPECT_DOUBLE_EQ(m.max_abs, 1.0);
}

TEST(Metrics, HandMadeTwoPixelImage) {
  Image a(2, 1), b(2, 1);
  a.at(0, 0) = Color(0.5f, 0.5f, 0.5f);
  b.at(0, 0) = Color(0.5f, 0.5f, 0.0f);  // one difference of 0.5, reference 0
  a.at(1, 0) = Color(1.0f, 2.0f, 3.0f);
  b.at(1, 0) = Color(1.0f, 1.0f, 3.0f);  // one difference of 1, reference 1
  const ErrorMetrics m = compare_images(a, b);
  EXPECT_DOUBLE_EQ(m.mse, (0.25 + 1.0) / 6.0);
  EXPECT_DOUBLE_EQ(m.relmse, (0.25 / 0.01 + 1.0 / 1.01) / 6.0);
  EXPECT_DOUBLE_EQ(m.max_abs, 1.0);
  EXPECT_NEAR(m.psnr, -10.0 * std::log10(m.mse), 1e-12);
}

TEST(Metrics, IdenticalImagesHaveZeroErrorAndInfinitePsnr) {
  const Image img(3, 2, Color(0.2f, 0.4f, 0.6f));
  const ErrorMetrics m = compare_images(img, img);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.relmse, 0.0);
  EXPECT_TRUE(std::isinf(m.psnr));
}

std::string message_of(const Image& a, const Image& b) {
  try {
    compare_images(a, b);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

TEST(Metrics, SizeMismatchNamesBothSizes) {
  EXPECT_EQ(message_of(Image(4, 3), Image(2, 2)), "image sizes differ: 4x3 vs 2x2");
}

TEST(Metrics, NonFiniteValuesAreRejected) {
  Image bad(2, 2);
  bad.at(1, 0) = Color(0, NAN, 0);
  EXPECT_EQ(message_of(bad, Image(2, 2)), "first image has a non-finite value at pixel (1, 0)");
  bad.at(1, 0) = Color(0);
  bad.at(0, 1) = Color(INFINITY);
  EXPECT_EQ(message_of(Image(2, 2), bad), "second image has a non-finite value at pixel (0, 1)");
  EXPECT_EQ(message_of(Image(), Image()), "cannot compare empty images");
}

}  // namespace
}  // namespace tuneray
