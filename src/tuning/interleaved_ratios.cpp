#include "tuning/interleaved_ratios.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "tuning/median_interval.h"
#include "tuning/stats.h"

namespace tuneray {

double student_t95(int dof) {
  if (dof < 1) throw std::invalid_argument("student_t95: degrees of freedom must be >= 1");
  // Two-sided 95 % (one-sided 0.975) quantiles for 1..30 degrees of freedom.
  static constexpr double kTable[30] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306,
                                        2.262,  2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120,
                                        2.110,  2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064,
                                        2.060,  2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof <= 30) return kTable[dof - 1];
  // Beyond the table: the normal quantile plus two terms of the Cornish-Fisher expansion,
  // within 0.001 of the exact value from 31 degrees of freedom on.
  const double z = 1.959964, z3 = z * z * z, z5 = z3 * z * z, n = dof;
  return z + (z3 + z) / (4 * n) + (5 * z5 + 16 * z3 + 3 * z) / (96 * n * n);
}

namespace {

// Mean and 95 % half-width of a sample's mean (0 half-width under two values).
void mean_interval(const std::vector<double>& x, double& mean, double& half_width) {
  const size_t n = x.size();
  double sum = 0;
  for (double v : x) sum += v;
  mean = sum / static_cast<double>(n);
  half_width = 0;
  if (n < 2) return;
  double squares = 0;
  for (double v : x) squares += (v - mean) * (v - mean);
  const double sd = std::sqrt(squares / static_cast<double>(n - 1));
  half_width = student_t95(static_cast<int>(n) - 1) * sd / std::sqrt(static_cast<double>(n));
}

}  // namespace

double RatioInterval::relative_half_width() const {
  if (!(ratio > 0)) return 0;
  return std::max(high / ratio, low > 0 ? ratio / low : std::numeric_limits<double>::infinity()) -
         1;
}

RatioInterval paired_ratio(const InterleavedResult& result, int i, int j,
                           RatioEstimator estimator) {
  const int count = static_cast<int>(result.costs.size());
  if (i < 0 || j < 0 || i >= count || j >= count)
    throw std::invalid_argument("paired_ratio: no candidate " + std::to_string(std::max(i, j)));
  const std::vector<double>& a = result.costs[i];
  const std::vector<double>& b = result.costs[j];
  if (a.empty() || a.size() != b.size())
    throw std::invalid_argument("paired_ratio: the candidates' rounds differ");
  std::vector<double> logs;
  for (size_t k = 0; k < a.size(); ++k) logs.push_back(std::log(a[k] / b[k]));
  RatioInterval r;
  if (estimator == RatioEstimator::kMedian) {
    // On the logarithms, so that an even count's median (the mean of the two middle logs, the
    // geometric mean of the two middle ratios) inverts exactly with the pair.
    const MedianInterval m = median_interval(logs);
    r.ratio = std::exp(m.median);
    r.low = std::exp(m.low);
    r.high = std::exp(m.high);
    r.confidence = m.confidence;
  } else {
    double mean = 0, half = 0;
    mean_interval(logs, mean, half);
    r.ratio = std::exp(mean);
    r.low = std::exp(mean - half);
    r.high = std::exp(mean + half);
  }
  r.median_cost = median(a);
  return r;
}

InterleavedResult measure_interleaved(int count, int reference,
                                      const std::function<double(int)>& measure,
                                      const InterleavedOptions& options) {
  if (count < 1 || reference < 0 || reference >= count)
    throw std::invalid_argument("measure_interleaved: reference " + std::to_string(reference) +
                                " is not one of " + std::to_string(count) + " candidates");
  if (options.min_rounds < 2 || options.max_rounds < options.min_rounds ||
      !(options.target_half_width > 0))
    throw std::invalid_argument(
        "measure_interleaved: need 2 <= min_rounds <= max_rounds and a positive target");
  InterleavedResult result;
  result.costs.resize(count);
  result.ratios.resize(count);
  for (int round = 0; round < options.max_rounds; ++round) {
    for (int k = 0; k < count; ++k) {
      const int i = (k + round) % count;  // rotated: nobody always goes first
      const double cost = measure(i);
      if (!(cost > 0) || !std::isfinite(cost))
        throw std::invalid_argument("measure_interleaved: candidate " + std::to_string(i) +
                                    " measured a cost of " + std::to_string(cost));
      result.costs[i].push_back(cost);
    }
    result.rounds = round + 1;
    if (result.rounds < options.min_rounds) continue;
    auto within = [&](const RatioInterval& r) {
      return r.confidence >= 0.95 && r.relative_half_width() <= options.target_half_width;
    };
    bool all_within = true;
    for (int i = 0; i < count; ++i) {
      result.ratios[i] = paired_ratio(result, i, reference, options.estimator);
      all_within &= within(result.ratios[i]);
    }
    // A pair's interval inverts exactly with the pair, so i over j covers j over i.
    for (int i = 0; i < count && options.every_pair; ++i)
      for (int j = i + 1; j < count; ++j)
        all_within &= within(paired_ratio(result, i, j, options.estimator));
    if (all_within) {
      result.converged = true;
      break;
    }
  }
  return result;
}

}  // namespace tuneray
