#include "render/adaptive_sampling.h"

#include <algorithm>
#include <cmath>

namespace tuneray {

std::vector<uint32_t> allocate_adaptive_samples(const Film& film, uint64_t budget) {
  const int w = film.width(), h = film.height();
  const size_t n_pixels = static_cast<size_t>(w) * h;
  std::vector<double> sigma(n_pixels), have(n_pixels);
  double sigma_sum = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      size_t i = static_cast<size_t>(y) * w + x;
      have[i] = film.samples(x, y);
      sigma[i] = std::sqrt(film.variance_of_mean(x, y) * have[i]);
      sigma_sum += sigma[i];
    }
  std::vector<uint32_t> extra(n_pixels, 0);
  if (n_pixels == 0 || budget == 0) return extra;
  double floor_sigma = 0.05 * sigma_sum / static_cast<double>(n_pixels);
  if (!(floor_sigma > 0)) floor_sigma = 1.0;  // no variance anywhere yet: spread evenly
  for (double& s : sigma) s += floor_sigma;

  auto spent = [&](double c) {
    double total = 0;
    for (size_t i = 0; i < n_pixels; ++i)
      total += std::floor(std::max(0.0, c * sigma[i] - have[i]));
    return total;
  };
  double lo = 0, hi = 1;
  while (spent(hi) < static_cast<double>(budget) && hi < 1e30) hi *= 2;
  for (int it = 0; it < 40; ++it) {
    double mid = 0.5 * (lo + hi);
    (spent(mid) <= static_cast<double>(budget) ? lo : hi) = mid;
  }
  for (size_t i = 0; i < n_pixels; ++i)
    extra[i] = static_cast<uint32_t>(std::floor(std::max(0.0, lo * sigma[i] - have[i])));
  return extra;
}

}  // namespace tuneray
