// Helpers shared by the tuner tests: Gaussian noise from our deterministic generator and a
// driver that runs a Nelder-Mead search against a cost function.
#pragma once

#include <cmath>
#include <functional>
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

}  // namespace tuneray::tuner::testing
