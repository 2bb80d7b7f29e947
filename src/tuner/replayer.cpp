#include "tuner/replayer.h"

#include <cmath>
#include <limits>

namespace tuneray::tuner {

void Replayer::add(const State& state, const Config& config, double cost) {
  recorded_[{state, config.to_string()}].costs.push_back(cost);
}

void Replayer::add_recorded(TuningDb& db, int64_t signature, const Space& space) {
  std::unordered_map<int64_t, State> states;
  for (const StoredState& s : db.states(signature)) states[s.id] = s.indicators;
  for (const StoredSample& sample : db.samples(signature)) {
    add(states.at(sample.state_id), space.parse(sample.config), sample.cost);
  }
}

ReplayResult Replayer::run(HybridTuner& tuner, const std::vector<State>& sequence,
                           int steps_per_state) {
  ReplayResult result;
  for (size_t index = 0; index < sequence.size(); ++index) {
    for (int step = 0; step < steps_per_state; ++step) {
      const Config config = tuner.suggest(sequence[index]);
      const TunerMode mode = tuner.mode();
      double cost = std::numeric_limits<double>::infinity();
      bool recorded = false;
      const auto it = recorded_.find({sequence[index], config.to_string()});
      if (it != recorded_.end() && !it->second.costs.empty()) {
        Recorded& r = it->second;
        cost = r.costs[r.next++ % r.costs.size()];
        recorded = true;
      } else if (fallback_) {
        cost = fallback_(sequence[index], config);
        ++result.unrecorded;
      } else {
        ++result.unrecorded;
      }
      tuner.report(config, cost);
      if (std::isfinite(cost)) result.total_cost += cost;
      result.steps.push_back({index, config, cost, recorded, mode});
    }
  }
  return result;
}

}  // namespace tuneray::tuner
