// Replayer: runs a HybridTuner against recorded costs instead of the application, so that
// strategies (epsilon, predictor, reward, search options) can be compared deterministically and
// in milliseconds.
//
// Costs are looked up by (state, configuration). When the tuner asks for a configuration more
// often than it was recorded, the recorded costs are cycled in recording order. A configuration
// never recorded for that state is costed by the fallback function if one is given, otherwise
// reported as a failure (and counted in ReplayResult::unrecorded).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "tuner/config.h"
#include "tuner/hybrid_tuner.h"
#include "tuner/indicators.h"
#include "tuner/tuning_db.h"

namespace tuneray::tuner {

struct ReplayStep {
  size_t state_index;  // index into the replayed sequence
  Config config;
  double cost;
  bool recorded;   // false: from the fallback or a failure
  TunerMode mode;  // the tuner's mode when it suggested the configuration
};

struct ReplayResult {
  std::vector<ReplayStep> steps;
  size_t unrecorded = 0;
  double total_cost = 0.0;  // sum of finite costs
};

class Replayer {
 public:
  using Fallback = std::function<double(const State&, const Config&)>;

  void add(const State& state, const Config& config, double cost);
  // Every sample recorded for `signature` in `db`; configurations are parsed with `space`.
  void add_recorded(TuningDb& db, int64_t signature, const Space& space);
  void set_fallback(Fallback fallback) { fallback_ = std::move(fallback); }

  // For each state of `sequence` in turn, `steps_per_state` suggest/report rounds.
  ReplayResult run(HybridTuner& tuner, const std::vector<State>& sequence, int steps_per_state);

 private:
  struct Recorded {
    std::vector<double> costs;
    size_t next = 0;
  };
  using Key = std::pair<State, std::string>;  // (raw state, Config::to_string())
  std::map<Key, Recorded> recorded_;
  Fallback fallback_;
};

}  // namespace tuneray::tuner
