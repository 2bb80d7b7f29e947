#include "render/adaptive_sampling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "render/neighbourhood_mean.h"

namespace tuneray {

namespace {

// Per-pixel sample variance (not of the mean), optionally averaged over the 3x3 neighbourhood.
std::vector<double> sample_variance(const Film& film, bool filter) {
  const int w = film.width(), h = film.height();
  std::vector<double> var(static_cast<size_t>(w) * h);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x)
      var[static_cast<size_t>(y) * w + x] = film.variance_of_mean(x, y) * film.samples(x, y);
  });
  return filter ? neighbourhood_mean(var, w, h) : var;
}

}  // namespace

std::vector<uint32_t> allocate_adaptive_samples(const Film& film, uint64_t budget,
                                                const AdaptiveOptions& options) {
  const size_t n_pixels = static_cast<size_t>(film.width()) * film.height();
  std::vector<uint32_t> extra(n_pixels, 0);
  if (n_pixels == 0 || budget == 0) return extra;

  std::vector<double> sigma = sample_variance(film, options.filter);
  std::vector<double> have(n_pixels);
  double sigma_sum = 0, have_sum = 0;
  for (size_t i = 0; i < n_pixels; ++i) {
    sigma[i] = std::sqrt(sigma[i]);
    sigma_sum += sigma[i];
    have[i] = film.samples(static_cast<int>(i % film.width()), static_cast<int>(i / film.width()));
    have_sum += have[i];
  }
  double floor_sigma = options.sigma_floor * sigma_sum / static_cast<double>(n_pixels);
  if (!(floor_sigma > 0)) floor_sigma = 1.0;  // no variance anywhere yet: spread evenly
  for (double& s : sigma) s += floor_sigma;
  const double cap =
      options.max_ratio > 0
          ? std::max(1.0, options.max_ratio * (have_sum + static_cast<double>(budget)) /
                              static_cast<double>(n_pixels))
          : 1e300;

  auto target = [&](double c, size_t i) {
    return std::floor(std::max(0.0, std::min(c * sigma[i], cap) - have[i]));
  };
  auto spent = [&](double c) {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n_pixels, 4096), 0.0,
        [&](const tbb::blocked_range<size_t>& r, double total) {
          for (size_t i = r.begin(); i != r.end(); ++i) total += target(c, i);
          return total;
        },
        std::plus<double>());
  };
  // The cap can make the budget unreachable: then every pixel below the cap gets filled to it.
  const double wanted = static_cast<double>(budget);
  double lo = 0, hi = 1;
  while (spent(hi) < wanted && hi < 1e30) hi *= 2;
  for (int it = 0; it < 60; ++it) {
    double mid = 0.5 * (lo + hi);
    double s = spent(mid);
    (s <= wanted ? lo : hi) = mid;
    if (s <= wanted && s >= 0.998 * wanted) break;  // close enough: rounding costs more
  }
  tbb::parallel_for(size_t{0}, n_pixels,
                    [&](size_t i) { extra[i] = static_cast<uint32_t>(target(lo, i)); });
  return extra;
}

}  // namespace tuneray
