#include "tuner/nearest_neighbour.h"

#include <cmath>
#include <stdexcept>

namespace tuneray::tuner {

void NearestNeighbourPredictor::set_best(int64_t state_id, std::span<const double> state,
                                         const Config& best) {
  const auto [it, inserted] = row_of_state_.try_emplace(state_id, rows_.size());
  if (!inserted) {
    rows_[it->second].best = best;
    return;
  }
  rows_.push_back({state_id, std::vector<double>(state.begin(), state.end()), best});
}

std::optional<NeighbourPrediction> NearestNeighbourPredictor::predict(
    std::span<const double> state) const {
  const Row* nearest = nullptr;
  double nearest_squared = 0.0;
  for (const Row& row : rows_) {
    if (row.state.size() != state.size()) {
      throw std::invalid_argument("NearestNeighbourPredictor: state dimension mismatch");
    }
    double squared = 0.0;
    for (size_t i = 0; i < state.size(); ++i) {
      squared += (row.state[i] - state[i]) * (row.state[i] - state[i]);
    }
    if (nearest == nullptr || squared < nearest_squared) {
      nearest = &row;
      nearest_squared = squared;
    }
  }
  if (nearest == nullptr) return std::nullopt;
  const double distance = std::sqrt(nearest_squared);
  return NeighbourPrediction{nearest->best, nearest->state_id, distance, distance <= threshold_};
}

}  // namespace tuneray::tuner
