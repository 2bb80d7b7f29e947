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
  sigma_sum += floor_sigma * static_cast<double>(n_pixels);
  const double cap =
      options.max_ratio > 0
          ? std::max(1.0, options.max_ratio * (have_sum + static_cast<double>(budget)) /
                              static_cast<double>(n_pixels))
          : 1e300;

  auto target = [&](double c, size_t i) {
    return std::max(0.0, std::min(c * sigma[i], cap) - have[i]);
  };
  // g(c): the samples the allocation for c would add before rounding, and its slope (the sum of
  // s_i over pixels that take samples and are below the cap). g is continuous, non-decreasing,
  // piecewise linear and convex until caps bind, so Newton steps from above land on the budget
  // in a few passes over the image (bisection on the rounded sum took 30-60 passes, a quarter
  // of an adaptive frame's time at 640x360); a bracket guards the steps when caps bind.
  struct Value {
    double g = 0, slope = 0;
    Value operator+(const Value& o) const { return {g + o.g, slope + o.slope}; }
  };
  auto evaluate = [&](double c) {
    return tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, n_pixels, 4096), Value{},
        [&](const tbb::blocked_range<size_t>& r, Value v) {
          // Four partial sums each: one running sum would make every pixel wait for the add
          // before it.
          double g[4] = {0, 0, 0, 0}, slope[4] = {0, 0, 0, 0};
          auto add = [&](size_t lane, size_t i) {
            double t = target(c, i);
            g[lane] += t;
            slope[lane] += t > 0 && c * sigma[i] < cap ? sigma[i] : 0.0;
          };
          size_t i = r.begin();
          for (; i + 4 <= r.end(); i += 4)
            for (size_t k = 0; k < 4; ++k) add(k, i + k);
          for (; i < r.end(); ++i) add(0, i);
          v.g += (g[0] + g[1]) + (g[2] + g[3]);
          v.slope += (slope[0] + slope[1]) + (slope[2] + slope[3]);
          return v;
        },
        std::plus<Value>());
  };
  // Row blocks round independently (below), each ending less than one sample above its share:
  // the search aims that many samples low so the total never exceeds the budget.
  const int block_rows = 16;
  const int blocks = (film.height() + block_rows - 1) / block_rows;
  const double wanted = std::max(0.0, static_cast<double>(budget) - blocks);
  if (wanted <= 0) return extra;
  const double tolerance = 0.5;  // samples
  double lo = 0, g_lo = 0;
  double hi = (have_sum + wanted) / sigma_sum;  // g(hi) >= wanted unless caps bind
  Value at_hi = evaluate(hi);
  for (int doubling = 0; at_hi.g <= wanted && doubling < 200; ++doubling) {
    lo = hi;
    g_lo = at_hi.g;
    hi *= 2;
    at_hi = evaluate(hi);
  }
  // Stays lo when the caps make the budget unreachable: every pixel is then filled to its cap.
  double c = lo;
  if (at_hi.g > wanted) {
    for (int it = 0; it < 60; ++it) {
      if (at_hi.g - wanted <= tolerance || wanted - g_lo <= tolerance) break;
      double next = at_hi.slope > 0 ? hi - (at_hi.g - wanted) / at_hi.slope : lo;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      Value v = evaluate(next);
      if (v.g > wanted) {
        hi = next;
        at_hi = v;
      } else {
        lo = next;
        g_lo = v.g;
      }
    }
    // hi only when it overshoots by less than the slack the rounding needs (see `wanted`).
    c = at_hi.g - wanted <= tolerance ? hi : lo;
  }

  // Rounding with the remainder carried to the next pixel realises fractional targets in
  // proportion (a 0.1-spp pass gives a tenth of the pixels one sample each, spread by their
  // targets); rounding each pixel down would give samples only to pixels owed a whole one.
  // Each row block starts from its own pseudo-random remainder so that no pixel is favoured
  // pass after pass.
  const int w = film.width();
  tbb::parallel_for(0, blocks, [&](int block) {
    uint64_t h = (budget + 0x9e3779b97f4a7c15ULL) * (2 * static_cast<uint64_t>(block) + 1);
    h ^= h >> 31;
    h *= 0xbf58476d1ce4e5b9ULL;
    h ^= h >> 29;
    double carry = static_cast<double>(h >> 11) * 0x1p-53;
    size_t begin = static_cast<size_t>(block) * block_rows * w;
    size_t end = std::min(n_pixels, begin + static_cast<size_t>(block_rows) * w);
    for (size_t i = begin; i < end; ++i) {
      double t = target(c, i);
      double k = std::min(std::floor(t + carry), std::floor(std::max(0.0, cap - have[i])));
      carry = t + carry - k;
      extra[i] = static_cast<uint32_t>(k);
    }
  });
  return extra;
}

}  // namespace tuneray
