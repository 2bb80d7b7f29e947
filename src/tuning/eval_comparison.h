// One camera's comparison (issue 12): every configuration the report compares at a camera — the
// default, native Embree, the search's converged configuration, its best sample and every
// prediction — measured in one time window, round-robin (tuning/interleaved_ratios.h), until
// the ratio between any two of them is known within ±3 % (95 % confidence) or a cap of rounds.
// A load change or a clock drift then hits every candidate alike instead of whichever happened
// to be measured at the time, and the best known configuration is the fastest candidate
// re-measured here, never one lucky search sample. Ratios are medians of the per-round ratios
// with order-statistic intervals (median_interval.h), so a frame stopped or slowed by a load
// spike moves neither, and the costs are derived from the same medians. The rounds are kept
// whole, so a study that reads a comparison back derives exactly what the run that measured it
// did, whichever estimator stopped it: comparisons stored when ratios were geometric means are
// read and derived like new ones.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tuning/eval_costs.h"
#include "tuning/eval_profile.h"
#include "tuning/interleaved_ratios.h"

namespace tuneray {

struct EvalComparison {
  std::vector<std::string> configs;        // AccelChoice texts, each once, in measuring order
  std::vector<std::vector<double>> costs;  // per configuration, its cost (ms) in each round
  bool within_target = false;  // every pair's interval reached the target before the cap

  int rounds() const { return costs.empty() ? 0 : static_cast<int>(costs.front().size()); }
  // The first configuration's (the default's, in comparison_configs) median cost over the
  // rounds, times the configuration's median per-round ratio to it: every cost in the units of
  // one yardstick measured in every round. A cost divided by the first configuration's is
  // exactly their paired ratio; between two others, medians not being transitive, the ratio of
  // their costs can differ from their paired ratio by the noise of the rounds, and the report's
  // ratios always come from ratio().
  double cost_ms(const std::string& config) const;
  // a / b: the median of the per-round ratios, with its order-statistic 95 % confidence
  // interval (under 6 rounds, stored by the earlier protocol, the range of the ratios).
  RatioInterval ratio(const std::string& a, const std::string& b) const;
  // The configuration of the lowest cost (the first of equals).
  const std::string& fastest() const;

 private:
  size_t index_of(const std::string& config) const;
};

// What one camera compares, in measuring order and each configuration once: the default
// configuration (the search space's), native Embree, then `converged`, `best_sample` and
// `predicted` (AccelChoice texts).
std::vector<std::string> comparison_configs(const std::string& default_config,
                                            const std::string& converged,
                                            const std::string& best_sample,
                                            const std::vector<std::string>& predicted);

// Rounds and target of the profile, over every pair, with the median estimator.
InterleavedOptions comparison_options(const EvalProfile& p);

// Measures `configs` at camera `camera`: one untimed frame of each first (a tree built for the
// first time pays for page faults and cold caches), then interleaved rounds, which stop when the
// comparison's own estimator, the median, has every pair within the target (whatever estimator
// `options` names). Throws std::runtime_error when a configuration's build is refused.
EvalComparison measure_comparison(EvalCostSource& costs, Objective objective, int camera,
                                  const std::vector<std::string>& configs,
                                  const InterleavedOptions& options);
// The same with any source of frames (`tune` measures its yardsticks this way): `frame(i)` renders
// one frame of configs[i]; `what` names the comparison in the refused-build error.
EvalComparison measure_comparison(const std::vector<std::string>& configs, Objective objective,
                                  const std::function<FrameCost(size_t)>& frame,
                                  const std::string& what, const InterleavedOptions& options);

// Exact both ways (every cost keeps its bits). Parsing throws std::runtime_error on malformed
// text and on costs that a comparison cannot hold (rounds of different lengths, a cost that is
// not positive).
std::string to_json(const EvalComparison& comparison);
EvalComparison parse_eval_comparison(const std::string& text);

}  // namespace tuneray
