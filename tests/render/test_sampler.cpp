#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "render/sampler.h"
#include "test_bsdf_chi2.h"

namespace tuneray {
namespace {

std::vector<float> sequence(Sampler& s, uint32_t x, uint32_t y, uint32_t index, int n) {
  s.start_pixel_sample(x, y, index);
  std::vector<float> v(n);
  for (float& f : v) f = s.next1();
  return v;
}

TEST(PcgSampler, SamePixelSampleRepeatsItsSequence) {
  PcgSampler a(42), b(42);
  auto first = sequence(a, 10, 20, 3, 64);
  sequence(a, 11, 20, 3, 17);  // unrelated work in between must not matter
  EXPECT_EQ(first, sequence(a, 10, 20, 3, 64));
  EXPECT_EQ(first, sequence(b, 10, 20, 3, 64));
  auto clone = a.clone();
  EXPECT_EQ(first, sequence(*clone, 10, 20, 3, 64));
}

TEST(PcgSampler, DifferentPixelsIndicesAndSeedsDiffer) {
  PcgSampler s(42), other_seed(43);
  auto base = sequence(s, 10, 20, 3, 16);
  EXPECT_NE(base, sequence(s, 11, 20, 3, 16));
  EXPECT_NE(base, sequence(s, 10, 21, 3, 16));
  EXPECT_NE(base, sequence(s, 20, 10, 3, 16));  // x and y are not interchangeable
  EXPECT_NE(base, sequence(s, 10, 20, 4, 16));
  EXPECT_NE(base, sequence(other_seed, 10, 20, 3, 16));
}

TEST(PcgSampler, ValuesAreUniformInUnitInterval) {
  PcgSampler s(1);
  const int bins = 20;
  std::vector<double> observed(bins, 0.0);
  double sum = 0;
  int n = 0;
  for (uint32_t p = 0; p < 2000; ++p) {
    s.start_pixel_sample(p % 50, p / 50, p % 7);
    for (int d = 0; d < 50; ++d) {
      float v = s.next1();
      ASSERT_GE(v, 0.0f);
      ASSERT_LT(v, 1.0f);
      sum += v;
      ++n;
      observed[static_cast<int>(v * bins)] += 1;
    }
  }
  // Mean of n uniforms: standard deviation 1 / sqrt(12 n); allow five of them.
  EXPECT_NEAR(sum / n, 0.5, 5.0 / std::sqrt(12.0 * n));
  std::vector<double> expected(bins, double(n) / bins);
  EXPECT_GT(testing::chi2_test(observed, expected).p_value, 1e-3);
}

TEST(PcgSampler, FirstDimensionIsUniformAcrossPixels) {
  // Decorrelation between pixels: the first value of neighbouring pixels must not cluster.
  PcgSampler s(5);
  const int bins = 16;
  std::vector<double> observed(bins, 0.0);
  int n = 0;
  for (uint32_t y = 0; y < 100; ++y) {
    for (uint32_t x = 0; x < 100; ++x) {
      s.start_pixel_sample(x, y, 0);
      observed[static_cast<int>(s.next1() * bins)] += 1;
      ++n;
    }
  }
  std::vector<double> expected(bins, double(n) / bins);
  EXPECT_GT(testing::chi2_test(observed, expected).p_value, 1e-3);
}

TEST(PcgSampler, Next2AndNext4FollowNext1) {
  PcgSampler s(9);
  auto ref = sequence(s, 4, 5, 6, 6);
  s.start_pixel_sample(4, 5, 6);
  std::array<float, 4> four = s.next4();
  Vec2f two = s.next2();
  EXPECT_EQ(std::vector<float>(four.begin(), four.end()),
            std::vector<float>(ref.begin(), ref.begin() + 4));
  EXPECT_EQ(two.x, ref[4]);
  EXPECT_EQ(two.y, ref[5]);
}

}  // namespace
}  // namespace tuneray
