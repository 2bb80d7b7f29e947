#include "render/film.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace tuneray {

template <typename Part>
Image Film::resolve_each(Part part) const {
  Image out(width(), height());
  tbb::parallel_for(tbb::blocked_range<int>(0, height()), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < width(); ++x) {
        const auto [sum, n] = part(pixel(x, y));
        out.at(x, y) = n > 0 ? sum / static_cast<float>(n) : Color(0.0f);
      }
  });
  return out;
}

Image Film::resolve() const {
  return resolve_each([](const Pixel& p) { return std::pair{p.sum(), p.samples()}; });
}

Image Film::resolve_half(int half) const {
  if (half != 0 && half != 1) throw std::invalid_argument("film: the halves are 0 and 1");
  return resolve_each([half](const Pixel& p) {
    return std::pair{p.half_sum[half], p.half_samples[half]};
  });
}

double Film::variance_of_mean(int x, int y) const {
  const Pixel& p = pixel(x, y);
  double n = p.samples();
  if (n < 2) return 0.0;
  const Color sum = p.sum();
  const SquareSum& sq = p.squares;
  // Per channel (n - 1) x the sample variance, sum of squares minus n x mean^2; two divisions
  // per pixel instead of seven (adaptive sampling reads every pixel every pass).
  const double inv_n = 1.0 / n;
  auto scaled_variance = [inv_n](double channel_sum, double square_sum) {
    return std::max(0.0, square_sum - channel_sum * channel_sum * inv_n);
  };
  return (scaled_variance(sum.x, sq.r) + scaled_variance(sum.y, sq.g) +
          scaled_variance(sum.z, sq.b)) /
         (3.0 * n * (n - 1));
}

uint64_t Film::total_samples() const {
  uint64_t total = 0;
  for (const Pixel& p : pixels_) total += p.samples();
  return total;
}

double Film::estimated_rmse() const {
  double total = 0;
  for (int y = 0; y < height(); ++y)
    for (int x = 0; x < width(); ++x) total += variance_of_mean(x, y);
  size_t n = static_cast<size_t>(width()) * height();
  return n > 0 ? std::sqrt(total / static_cast<double>(n)) : 0.0;
}

double Film::mean_value_length() const {
  double total = 0;
  size_t counted = 0;
  for (int y = 0; y < height(); ++y)
    for (int x = 0; x < width(); ++x) {
      const Pixel& p = pixel(x, y);
      const uint32_t n = p.samples();
      if (n == 0) continue;
      total += length(p.sum()) / n;
      ++counted;
    }
  return counted > 0 ? total / static_cast<double>(counted) : 0.0;
}

void Film::clear() {
  std::fill(pixels_.begin(), pixels_.end(), Pixel{});
}

}  // namespace tuneray
