// Comparisons that a noisy machine cannot fool (issue 12): the candidates are measured in the
// same time window, round-robin with the order rotated every round (a load change or a clock
// drift then hits every candidate alike), and the rounds go on until the 95 % confidence
// interval of each candidate's cost ratio to the reference is within a target half-width, or a
// cap is reached. Each ratio is the geometric mean of the per-round ratios (the rounds pair
// measurements taken moments apart); its interval comes from Student's t on the logarithms.
#pragma once

#include <functional>
#include <vector>

namespace tuneray {

struct RatioInterval {
  double ratio = 0;          // candidate cost / reference cost, geometric mean over rounds
  double low = 0, high = 0;  // 95 % confidence interval of the ratio
  double median_cost = 0;    // the candidate's median cost over the rounds
  // Half-width relative to the ratio: max(high / ratio, ratio / low) - 1 (the interval is
  // symmetric on a log scale, so both give the same).
  double relative_half_width() const { return ratio > 0 ? high / ratio - 1 : 0; }
};

struct InterleavedResult {
  std::vector<RatioInterval> ratios;       // one per candidate; the reference's is exactly 1
  std::vector<std::vector<double>> costs;  // per candidate, one cost per round
  int rounds = 0;
  bool converged = false;  // every watched interval within the target before the cap
};

// The paired ratio of candidate `i` to candidate `j` over the rounds of `result` (any two
// candidates, not only against the reference), with its 95 % interval.
RatioInterval paired_ratio(const InterleavedResult& result, int i, int j);

struct InterleavedOptions {
  double target_half_width = 0.03;  // ±3 %
  int min_rounds = 3;
  int max_rounds = 30;
  // Go on until the ratio between any two candidates is within the target, not only each
  // candidate's ratio to the reference: for a report that takes ratios between any of them.
  bool every_pair = false;
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
