// A distribution-free confidence interval for a median, from order statistics: whatever the
// distribution, each value lies below the median with probability 1/2, so the number below it
// is Binomial(n, 1/2) and the interval between the sorted sample's values of ranks l and
// n + 1 - l misses the median with probability 2 P(B <= l - 1). Nothing but that is assumed, so
// a few wild values (a stopped process, a load spike) move neither the median nor the interval
// unless they reach its ranks.
#pragma once

#include <optional>
#include <vector>

namespace tuneray {

struct OrderStatisticRanks {
  int low = 0, high = 0;  // 1-based ranks in the sorted sample; high = n + 1 - low
  double confidence = 0;  // exact coverage: 1 - 2 P(B <= low - 1), B ~ Binomial(n, 1/2)
};

// The narrowest symmetric pair of ranks whose interval covers the median with at least `level`
// confidence (level in (0, 1)); none when even the whole sample's range covers it less often,
// as for n < 6 at 95 % (the range of 5 values misses the median with probability 1/16).
std::optional<OrderStatisticRanks> median_interval_ranks(int n, double level = 0.95);

struct MedianInterval {
  double median = 0;         // middle value, or the mean of the two middle values
  double low = 0, high = 0;  // the order statistics of median_interval_ranks
  // The interval's exact coverage; below `level` only when the sample is too small for any
  // ranks, and the interval is then the sample's whole range.
  double confidence = 0;
};

// Of a non-empty sample (std::invalid_argument otherwise).
MedianInterval median_interval(std::vector<double> values, double level = 0.95);

}  // namespace tuneray
