#include "tuner/latin_hypercube.h"

#include <numeric>

namespace tuneray::tuner {

std::vector<std::vector<double>> latin_hypercube(size_t count, size_t dims, Rng& rng) {
  std::vector<std::vector<double>> points(count, std::vector<double>(dims));
  std::vector<size_t> strata(count);
  for (size_t d = 0; d < dims; ++d) {
    std::iota(strata.begin(), strata.end(), size_t{0});
    // Fisher-Yates with our own generator so the result is the same on every platform.
    for (size_t i = count; i > 1; --i) std::swap(strata[i - 1], strata[rng.below(i)]);
    for (size_t i = 0; i < count; ++i) {
      points[i][d] = (static_cast<double>(strata[i]) + rng.uniform()) / static_cast<double>(count);
    }
  }
  return points;
}

}  // namespace tuneray::tuner
