#include "render/film.h"

#include <algorithm>
#include <cmath>

namespace tuneray {

Image Film::resolve() const {
  Image out(width(), height());
  for (int y = 0; y < height(); ++y)
    for (int x = 0; x < width(); ++x) {
      uint32_t n = samples(x, y);
      out.at(x, y) = n > 0 ? sum_.at(x, y) / static_cast<float>(n) : Color(0.0f);
    }
  return out;
}

double Film::variance_of_mean(int x, int y) const {
  size_t i = static_cast<size_t>(y) * width() + x;
  double n = samples_[i];
  if (n < 2) return 0.0;
  const Color& sum = sum_.at(x, y);
  const SquareSum& sq = square_sum_[i];
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
  for (uint32_t n : samples_) total += n;
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
      uint32_t n = samples(x, y);
      if (n == 0) continue;
      total += length(sum_.at(x, y)) / n;
      ++counted;
    }
  return counted > 0 ? total / static_cast<double>(counted) : 0.0;
}

void Film::clear() {
  std::fill(square_sum_.begin(), square_sum_.end(), SquareSum{});
  std::fill(sum_.data(), sum_.data() + sum_.pixel_count(), Color(0.0f));
  std::fill(samples_.begin(), samples_.end(), 0u);
  for (int h = 0; h < 2; ++h) {
    std::fill(half_sum_[h].data(), half_sum_[h].data() + half_sum_[h].pixel_count(), Color(0.0f));
    std::fill(half_samples_[h].begin(), half_samples_[h].end(), 0u);
  }
}

}  // namespace tuneray
