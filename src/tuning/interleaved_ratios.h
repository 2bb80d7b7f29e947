// Comparisons that a noisy machine cannot fool (issue 12): the candidates are measured in the
// same time window, round-robin with the order rotated every round (a load change or a clock
// drift then hits every candidate alike), and the rounds go on until the 95 % confidence
// interval of each candidate's cost ratio to the reference is within a target half-width, or a
// cap is reached. The rounds pair measurements taken moments apart, so each ratio is estimated
// from the per-round ratios: by their geometric mean with Student's t on the logarithms, or by
// their median with a distribution-free order-statistic interval (median_interval.h), which one
// stopped frame cannot move.
#pragma once

#include <functional>
#include <vector>

namespace tuneray {

enum class RatioEstimator {
  kGeometricMean,  // of the per-round ratios; Student's t interval on their logarithms
  kMedian,         // of the per-round ratios; order-statistic interval (binomial ranks)
};

struct RatioInterval {
  double ratio = 0;          // candidate cost / reference cost, estimated over the rounds
  double low = 0, high = 0;  // 95 % confidence interval of the ratio
  // The interval's confidence: 0.95 for Student's t; the exact coverage of the order
  // statistics for the median (>= 0.95, or below it under 6 rounds, where no ranks reach 95 %
  // and the interval is the whole range of the per-round ratios).
  double confidence = 0.95;
  double median_cost = 0;  // the candidate's median cost over the rounds
  // Half-width relative to the ratio: max(high / ratio, ratio / low) - 1 (equal for Student's
  // t, symmetric on a log scale; the order statistics need not be).
  double relative_half_width() const;
};

struct InterleavedResult {
  std::vector<RatioInterval> ratios;       // one per candidate; the reference's is exactly 1
  std::vector<std::vector<double>> costs;  // per candidate, one cost per round
  int rounds = 0;
  bool converged = false;  // every watched interval within the target before the cap
};

// The paired ratio of candidate `i` to candidate `j` over the rounds of `result` (any two
// candidates, not only against the reference), with its 95 % interval. Either estimator gives
// exactly the inverse ratio and interval for `j` over `i`.
RatioInterval paired_ratio(const InterleavedResult& result, int i, int j,
                           RatioEstimator estimator = RatioEstimator::kGeometricMean);

struct InterleavedOptions {
  double target_half_width = 0.03;  // ±3 %
  int min_rounds = 3;
  int max_rounds = 30;
  // Go on until the ratio between any two candidates is within the target, not only each
  // candidate's ratio to the reference: for a report that takes ratios between any of them.
  bool every_pair = false;
  // A round stops the comparison only when every watched interval is within the target at 95 %
  // confidence or more: with the median, never before 6 rounds.
  RatioEstimator estimator = RatioEstimator::kGeometricMean;
};

// `measure(i)` returns one cost (> 0, e.g. ms) of candidate i; `count` candidates, ratios taken
// to candidate `reference`. Throws std::invalid_argument on bad arguments or a cost that is not
// a positive finite number.
InterleavedResult measure_interleaved(int count, int reference,
                                      const std::function<double(int)>& measure,
                                      const InterleavedOptions& options = {});

// Two-sided 95 % quantile of Student's t with `dof` degrees of freedom (dof >= 1).
double student_t95(int dof);

}  // namespace tuneray
