// Nearest-neighbour predictor: for every known state the best configuration seen so far; an
// unknown state gets the configuration of the nearest known state (Euclidean distance between
// normalised indicator vectors). The table is small (one row per state) and a linear scan over
// it costs microseconds for thousands of states, so no spatial index is kept.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "tuner/config.h"

namespace tuneray::tuner {

struct NeighbourPrediction {
  Config config;
  int64_t state_id = -1;  // the known state the configuration comes from
  double distance = 0.0;  // normalised distance to that state
  bool known = true;      // false when farther than the predictor's threshold
};

class NearestNeighbourPredictor {
 public:
  // States farther than `threshold` from every known state are reported as unknown (the
  // prediction is still filled in, so a search can warm-start from it). Default: never unknown.
  explicit NearestNeighbourPredictor(double threshold = std::numeric_limits<double>::infinity())
      : threshold_(threshold) {}

  // Records (or replaces) the best configuration of a state.
  void set_best(int64_t state_id, std::span<const double> normalised_state, const Config& best);
  std::optional<NeighbourPrediction> predict(std::span<const double> normalised_state) const;

  size_t size() const { return rows_.size(); }
  double threshold() const { return threshold_; }

 private:
  struct Row {
    int64_t state_id;
    std::vector<double> state;
    Config best;
  };
  double threshold_;
  std::vector<Row> rows_;
  std::unordered_map<int64_t, size_t> row_of_state_;
};

}  // namespace tuneray::tuner
