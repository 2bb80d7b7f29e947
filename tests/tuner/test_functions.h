// Helpers shared by the tuner tests: Gaussian noise from our deterministic generator and a
// driver that runs a Nelder-Mead search against a cost function.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <optional>
#include <unordered_map>
#include <vector>

#include "tuner/config.h"
#include "tuner/nelder_mead.h"
#include "tuner/rng.h"

namespace tuneray::tuner::testing {

inline double gaussian(Rng& rng) {
  // Box-Muller; 1 - uniform() is in (0, 1] so the logarithm is finite.
  return std::sqrt(-2.0 * std::log(1.0 - rng.uniform())) *
         std::cos(6.283185307179586 * rng.uniform());
}

struct SearchRun {
  Config incumbent;
  int measurements = 0;
  std::unordered_map<Config, std::vector<double>> table;
};

inline SearchRun run_search(NelderMead& search, const std::function<double(const Config&)>& cost) {
  SearchRun run;
  const NelderMead::Lookup lookup = [&run](const Config& c) -> const std::vector<double>* {
    const auto it = run.table.find(c);
    return it == run.table.end() ? nullptr : &it->second;
  };
  while (std::optional<Config> next = search.next(lookup)) {
    run.table[*next].push_back(cost(*next));
    ++run.measurements;
  }
  run.incumbent = search.incumbent();
  return run;
}

// Costs recorded per configuration, and the lookup a search reads them through.
struct CostTable {
  std::unordered_map<Config, std::vector<double>> costs;
  NelderMead::Lookup lookup() {
    return [this](const Config& c) -> const std::vector<double>* {
      const auto it = costs.find(c);
      return it == costs.end() ? nullptr : &it->second;
    };
  }
};

// Runs `a` and `b` side by side for up to `steps` requests against one table (each request
// measured once, by `cost`): they must ask for the same configurations and finish together.
inline void expect_same_requests(NelderMead& a, NelderMead& b, CostTable& table,
                                 const std::function<double(const Config&)>& cost, int steps) {
  const NelderMead::Lookup lookup = table.lookup();
  for (int i = 0; i < steps; ++i) {
    const std::optional<Config> next_a = a.next(lookup);
    const std::optional<Config> next_b = b.next(lookup);
    ASSERT_EQ(next_a.has_value(), next_b.has_value()) << "request " << i;
    if (!next_a) return;
    EXPECT_EQ(*next_a, *next_b) << "request " << i;
    table.costs[*next_a].push_back(cost(*next_a));
  }
}

}  // namespace tuneray::tuner::testing
