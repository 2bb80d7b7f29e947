#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "render/blue_noise_sampler.h"
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

TEST(Pcg32x4, EachLaneIsItsScalarGenerator) {
  Pcg32 scalar[4] = {Pcg32(1, 2), Pcg32(3, 4), Pcg32(0xfffffffffffULL, 7), Pcg32(9, 0)};
  Pcg32 copies[4] = {scalar[0], scalar[1], scalar[2], scalar[3]};
  Pcg32* lanes[4] = {&copies[0], &copies[1], &copies[2], &copies[3]};
  Pcg32x4 x(lanes);
  for (int n = 0; n < 1000; ++n) {
    alignas(16) float u[4];
    _mm_store_ps(u, x.next_floats());
    for (int i = 0; i < 4; ++i) ASSERT_EQ(u[i], scalar[i].next_float()) << n << " " << i;
  }
  x.store(lanes);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(copies[i].next_u32(), scalar[i].next_u32());
}

// A bank's slot draws what a lone sampler started at the same pixel sample draws, whichever way
// the bank steps it (four generators side by side, or one by one; blue noise in and past its
// tables, and past its samples).
template <class S>
void expect_bank_is_lone_samplers(const S& prototype) {
  std::unique_ptr<SamplerBank> bank = prototype.make_bank();
  std::vector<PixelSampleId> ids;
  // Coordinates with high bits too: the seeding mixes them as one 64-bit word.
  for (uint32_t k = 0; k < 11; ++k)
    ids.push_back({k % 5 + k * 390451573u, k / 5 + k * 2654435761u, k * 37 % 300});
  std::vector<float> first(4 * ids.size());
  float* first4[4];
  for (int j = 0; j < 4; ++j) first4[j] = first.data() + j * ids.size();
  bank->start(0, ids, first4);
  std::vector<S> lone(ids.size(), prototype);
  for (size_t k = 0; k < ids.size(); ++k) {
    lone[k].start_pixel_sample(ids[k].x, ids[k].y, ids[k].index);
    const std::array<float, 4> u = lone[k].next4();
    for (int j = 0; j < 4; ++j) ASSERT_EQ(first4[j][k], u[j]);
  }
  std::vector<float> out(8 * ids.size());
  float* planes[8];
  for (int j = 0; j < 8; ++j) planes[j] = out.data() + j * ids.size();
  for (int round = 0; round < 5; ++round) {
    // Every slot but the fourth, at reversed positions, or in odd rounds side by side (where
    // four slots' numbers are stored together).
    std::vector<uint32_t> slots, positions;
    for (uint32_t k = 0; k < ids.size(); ++k) {
      if (k == 3) continue;
      slots.push_back(k);
      positions.push_back(round % 2 ? static_cast<uint32_t>(slots.size() - 1)
                                    : static_cast<uint32_t>(ids.size() - 1 - k));
    }
    bank->next4(slots, positions, 2, planes);
    for (size_t i = 0; i < slots.size(); ++i) {
      S& s = lone[slots[i]];
      const std::array<float, 4> a = s.next4(), b = s.next4();
      for (int j = 0; j < 4; ++j) {
        ASSERT_EQ(planes[j][positions[i]], a[j]) << round << " " << slots[i];
        ASSERT_EQ(planes[4 + j][positions[i]], b[j]) << round << " " << slots[i];
      }
    }
  }
}

TEST(SamplerBank, SlotsDrawWhatLoneSamplersDraw) {
  expect_bank_is_lone_samplers(PcgSampler(42));
  expect_bank_is_lone_samplers(BlueNoiseSampler(7));
}

}  // namespace
}  // namespace tuneray
