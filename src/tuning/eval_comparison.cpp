#include "tuning/eval_comparison.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tuning/accel_choice.h"
#include "tuning/stats.h"

namespace tuneray {

namespace {

using nlohmann::json;

void check_costs(const EvalComparison& c) {
  if (c.configs.empty() || c.costs.size() != c.configs.size())
    throw std::runtime_error("a comparison needs one list of costs per configuration");
  for (const std::vector<double>& costs : c.costs) {
    if (costs.empty() || costs.size() != c.costs.front().size())
      throw std::runtime_error("a comparison's configurations must have the same rounds");
    for (double ms : costs)
      if (!(ms > 0) || !std::isfinite(ms))
        throw std::runtime_error(fmt::format("a comparison holds a cost of {} ms", ms));
  }
}

}  // namespace

size_t EvalComparison::index_of(const std::string& config) const {
  for (size_t i = 0; i < configs.size(); ++i)
    if (configs[i] == config) return i;
  throw std::out_of_range("the comparison did not measure " + config);
}

double EvalComparison::cost_ms(const std::string& config) const {
  // The yardstick's own ratio is exactly 1, so its cost is its plain median.
  return median(costs.at(0)) * ratio(config, configs.at(0)).ratio;
}

RatioInterval EvalComparison::ratio(const std::string& a, const std::string& b) const {
  InterleavedResult rounds;
  rounds.costs = costs;
  return paired_ratio(rounds, static_cast<int>(index_of(a)), static_cast<int>(index_of(b)),
                      RatioEstimator::kMedian);
}

const std::string& EvalComparison::fastest() const {
  size_t best = 0;
  double best_ms = cost_ms(configs.at(0));
  for (size_t i = 1; i < configs.size(); ++i)
    if (const double ms = cost_ms(configs[i]); ms < best_ms) {
      best = i;
      best_ms = ms;
    }
  return configs[best];
}

std::vector<std::string> comparison_configs(const std::string& default_config,
                                            const std::string& converged,
                                            const std::string& best_sample,
                                            const std::vector<std::string>& predicted) {
  std::vector<std::string> configs = {default_config, AccelChoice::native().to_string()};
  auto add = [&](const std::string& config) {
    if (std::find(configs.begin(), configs.end(), config) == configs.end())
      configs.push_back(config);
  };
  add(converged);
  add(best_sample);
  for (const std::string& config : predicted) add(config);
  return configs;
}

InterleavedOptions comparison_options(const EvalProfile& p) {
  InterleavedOptions o;
  o.min_rounds = p.compare_min_rounds;
  o.max_rounds = p.compare_max_rounds;
  o.target_half_width = p.compare_target;
  o.every_pair = true;
  o.estimator = RatioEstimator::kMedian;
  return o;
}

EvalComparison measure_comparison(EvalCostSource& costs, Objective objective, int camera,
                                  const std::vector<std::string>& configs,
                                  const InterleavedOptions& options) {
  std::vector<AccelChoice> choices;
  for (const std::string& config : configs) choices.push_back(parse_accel_choice(config));
  return measure_comparison(
      configs, objective, [&](size_t i) { return costs.frame(choices[i], camera); },
      fmt::format("camera {}", camera), options);
}

EvalComparison measure_comparison(const std::vector<std::string>& configs, Objective objective,
                                  const std::function<FrameCost(size_t)>& frame,
                                  const std::string& what, const InterleavedOptions& options) {
  auto frame_ms = [&](size_t i) {
    const FrameCost cost = frame(i);
    if (!cost.ok)
      throw std::runtime_error(
          fmt::format("{}: comparing {}: the build was refused: {}", what, configs[i], cost.error));
    return cost.cost_ms(objective);
  };
  for (size_t i = 0; i < configs.size(); ++i) frame_ms(i);
  InterleavedOptions median_options = options;
  median_options.estimator = RatioEstimator::kMedian;  // what EvalComparison derives
  const InterleavedResult measured = measure_interleaved(
      static_cast<int>(configs.size()), 0, [&](int i) { return frame_ms(static_cast<size_t>(i)); },
      median_options);
  EvalComparison c;
  c.configs = configs;
  c.costs = measured.costs;
  c.within_target = measured.converged;
  return c;
}

std::string to_json(const EvalComparison& c) {
  return json{{"configs", c.configs}, {"costs", c.costs}, {"within_target", c.within_target}}
      .dump();
}

EvalComparison parse_eval_comparison(const std::string& text) {
  EvalComparison c;
  try {
    const json j = json::parse(text);
    c.configs = j.at("configs").get<std::vector<std::string>>();
    c.costs = j.at("costs").get<std::vector<std::vector<double>>>();
    c.within_target = j.at("within_target").get<bool>();
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("malformed comparison: ") + e.what());
  }
  check_costs(c);
  return c;
}

}  // namespace tuneray
