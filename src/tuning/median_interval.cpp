#include "tuning/median_interval.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tuneray {

namespace {

// P(B = k) for B ~ Binomial(n, 1/2), in log space (2^-n underflows beyond n = 1074).
double binomial_half_pmf(int n, int k) {
  return std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0) -
                  n * std::log(2.0));
}

}  // namespace

std::optional<OrderStatisticRanks> median_interval_ranks(int n, double level) {
  if (n < 1 || !(level > 0 && level < 1))
    throw std::invalid_argument("median_interval_ranks: need n >= 1 and a level in (0, 1)");
  const double tail = (1 - level) / 2;
  // The largest l with P(B <= l - 1) <= tail: the narrowest interval that still covers.
  int low = 0;
  double below = 0;  // P(B <= low - 1)
  while (low + 1 <= (n + 1) / 2) {
    const double next = below + binomial_half_pmf(n, low);  // P(B <= low)
    if (next > tail) break;
    below = next;
    ++low;
  }
  if (low == 0) return std::nullopt;
  return OrderStatisticRanks{low, n + 1 - low, 1 - 2 * below};
}

MedianInterval median_interval(std::vector<double> values, double level) {
  const int n = static_cast<int>(values.size());
  if (n == 0) throw std::invalid_argument("median_interval: no values");
  std::sort(values.begin(), values.end());
  MedianInterval m;
  m.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  if (const auto ranks = median_interval_ranks(n, level)) {
    m.low = values[ranks->low - 1];
    m.high = values[ranks->high - 1];
    m.confidence = ranks->confidence;
  } else {
    m.low = values.front();
    m.high = values.back();
    m.confidence = 1 - 2 * std::pow(0.5, n);  // the range misses when all fall on one side
  }
  return m;
}

}  // namespace tuneray
