// The 3x3 neighbourhood mean: exact values at the border, and its two implementations (masked,
// for data with holes; separable, for data without) agreeing on random images.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "render/neighbourhood_mean.h"

namespace tuneray {
namespace {

std::vector<double> random_values(int width, int height, uint32_t seed, bool holes) {
  std::vector<double> v(static_cast<size_t>(width) * height);
  for (double& x : v) {
    seed = seed * 1664525u + 1013904223u;
    x = static_cast<double>(seed >> 8) * 0x1p-24 * 10.0;
    if (holes && (seed >> 4) % 5 == 0) x = -1;
  }
  return v;
}

TEST(NeighbourhoodMean, ExactAtCornersEdgesAndInside) {
  // 3 x 3:  1 2 3 / 4 5 6 / 7 8 9
  std::vector<double> v = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  std::vector<double> m = neighbourhood_mean(v, 3, 3);
  EXPECT_DOUBLE_EQ(m[0], (1 + 2 + 4 + 5) / 4.0);
  EXPECT_DOUBLE_EQ(m[1], (1 + 2 + 3 + 4 + 5 + 6) / 6.0);
  EXPECT_DOUBLE_EQ(m[4], 5.0);
  EXPECT_DOUBLE_EQ(m[8], (5 + 6 + 8 + 9) / 4.0);
  // One row and one column: the window clips to what exists.
  std::vector<double> row = {2, 4, 9};
  EXPECT_DOUBLE_EQ(neighbourhood_mean(row, 3, 1)[0], 3.0);
  EXPECT_DOUBLE_EQ(neighbourhood_mean(row, 1, 3)[1], 5.0);
}

TEST(NeighbourhoodMean, SeparableAgreesWithMaskedWithoutHoles) {
  for (auto [w, h] : {std::pair{37, 23}, std::pair{1, 5}, std::pair{6, 1}, std::pair{2, 2}}) {
    std::vector<double> v = random_values(w, h, 7u + static_cast<uint32_t>(w), false);
    std::vector<double> a = detail::neighbourhood_mean_masked(v, w, h);
    std::vector<double> b = detail::neighbourhood_mean_separable(v, w, h);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-12 * (1 + a[i])) << i;
  }
}

TEST(NeighbourhoodMean, HolesAreLeftOut) {
  std::vector<double> v = random_values(19, 11, 3u, true);
  EXPECT_EQ(neighbourhood_mean(v, 19, 11), detail::neighbourhood_mean_masked(v, 19, 11));
  std::vector<double> one_hole = {-1, 4, 4, 4};  // 2 x 2: the hole does not count
  for (double m : neighbourhood_mean(one_hole, 2, 2)) EXPECT_DOUBLE_EQ(m, 4.0);
  std::vector<double> all_holes = {-1, -1};
  for (double m : neighbourhood_mean(all_holes, 2, 1)) EXPECT_DOUBLE_EQ(m, 0.0);
}

}  // namespace
}  // namespace tuneray
