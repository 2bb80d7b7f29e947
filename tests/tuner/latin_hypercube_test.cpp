#include "tuner/latin_hypercube.h"

#include <gtest/gtest.h>

#include <vector>

namespace tuneray::tuner {
namespace {

TEST(LatinHypercube, OneSamplePerStratumPerDimension) {
  for (size_t count : {1u, 2u, 7u, 50u}) {
    Rng rng(count);
    const auto points = latin_hypercube(count, 5, rng);
    ASSERT_EQ(points.size(), count);
    for (size_t d = 0; d < 5; ++d) {
      std::vector<int> hits(count, 0);
      for (const auto& p : points) {
        ASSERT_GE(p[d], 0.0);
        ASSERT_LT(p[d], 1.0);
        ++hits[static_cast<size_t>(p[d] * static_cast<double>(count))];
      }
      for (size_t s = 0; s < count; ++s) EXPECT_EQ(hits[s], 1) << "dim " << d << " stratum " << s;
    }
  }
}

TEST(LatinHypercube, SameSeedSamePoints) {
  Rng a(9);
  Rng b(9);
  EXPECT_EQ(latin_hypercube(10, 3, a), latin_hypercube(10, 3, b));
}

}  // namespace
}  // namespace tuneray::tuner
