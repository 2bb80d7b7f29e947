#include "tuner/greedy_gq.h"

#include <cmath>
#include <stdexcept>

#include "tuner/latin_hypercube.h"
#include "tuner/rng.h"
#include "tuner/token_io.h"

namespace tuneray::tuner {

GreedyGqPredictor::GreedyGqPredictor(size_t state_dims, size_t config_dims,
                                     const GreedyGqOptions& options, uint64_t seed)
    : state_dims_(state_dims), config_dims_(config_dims), options_(options) {
  if (!(options.width > 0.0) || !(options.step_size > 0.0)) {
    throw std::invalid_argument("GreedyGqPredictor: width and step size must be positive");
  }
  if (options.replays_per_sample < 0) {
    throw std::invalid_argument("GreedyGqPredictor: replays per sample must be >= 0");
  }
  const size_t dims = state_dims + config_dims;
  const auto count = static_cast<size_t>(std::ceil(options.centres_per_dimension * dims));
  Rng rng(seed ^ 0x5eedc3e7ULL);
  centres_ = latin_hypercube(count, dims, rng);
  theta_.assign(centres_.size() + 1, 0.0);
}

void GreedyGqPredictor::features(std::span<const double> state, std::span<const double> config,
                                 std::vector<double>& phi) const {
  if (state.size() != state_dims_ || config.size() != config_dims_) {
    throw std::invalid_argument("GreedyGqPredictor: dimension mismatch");
  }
  const double inverse_width_squared = 1.0 / (options_.width * options_.width);
  phi.resize(centres_.size() + 1);
  for (size_t j = 0; j < centres_.size(); ++j) {
    const double* c = centres_[j].data();
    double squared = 0.0;
    for (size_t i = 0; i < state_dims_; ++i) squared += (state[i] - c[i]) * (state[i] - c[i]);
    c += state_dims_;
    for (size_t i = 0; i < config_dims_; ++i) squared += (config[i] - c[i]) * (config[i] - c[i]);
    phi[j] = std::exp(-squared * inverse_width_squared);
  }
  phi.back() = 1.0;
}

void GreedyGqPredictor::train(std::span<const double> state, std::span<const double> config,
                              double reward) {
  features(state, config, scratch_);
  train_features(scratch_, reward);
  remember(state, config, reward);
  if (memory_.empty()) return;
  for (int k = 0; k < options_.replays_per_sample; ++k) {
    // splitmix64 of the update count: uniform draws that a replay of the same samples repeats.
    const uint64_t z = splitmix64_mix(updates_ * 0x9e3779b97f4a7c15ULL + 0x632be59bd9b4e019ULL);
    const Remembered& sample = memory_[z % memory_.size()];
    const std::span<const double> point(sample.point);
    features(point.first(state_dims_), point.subspan(state_dims_), scratch_);
    train_features(scratch_, sample.reward);
  }
}

void GreedyGqPredictor::remember(std::span<const double> state, std::span<const double> config,
                                 double reward) {
  if (state.size() != state_dims_ || config.size() != config_dims_) {
    throw std::invalid_argument("GreedyGqPredictor: dimension mismatch");
  }
  if (options_.replay_memory == 0) return;
  Remembered sample{std::vector<double>(state.begin(), state.end()), reward};
  sample.point.insert(sample.point.end(), config.begin(), config.end());
  if (memory_.size() < options_.replay_memory) {
    memory_.push_back(std::move(sample));
    return;
  }
  memory_[memory_next_] = std::move(sample);
  memory_next_ = (memory_next_ + 1) % memory_.size();
}

std::vector<double> GreedyGqPredictor::feature_vector(std::span<const double> state,
                                                      std::span<const double> config) const {
  std::vector<double> phi;
  features(state, config, phi);
  return phi;
}

void GreedyGqPredictor::train_features(std::span<const double> phi, double reward) {
  if (phi.size() != theta_.size())
    throw std::invalid_argument("GreedyGqPredictor: feature vector of the wrong size");
  double prediction = 0.0;
  double norm_squared = 0.0;
  for (size_t j = 0; j < phi.size(); ++j) {
    prediction += theta_[j] * phi[j];
    norm_squared += phi[j] * phi[j];
  }
  const double step = options_.step_size * (reward - prediction) / norm_squared;
  for (size_t j = 0; j < phi.size(); ++j) theta_[j] += step * phi[j];
  ++updates_;
}

double GreedyGqPredictor::value(std::span<const double> state,
                                std::span<const double> config) const {
  features(state, config, scratch_);
  double q = 0.0;
  for (size_t j = 0; j < scratch_.size(); ++j) q += theta_[j] * scratch_[j];
  return q;
}

std::optional<size_t> GreedyGqPredictor::best_candidate(
    std::span<const double> state, const std::vector<std::vector<double>>& candidates) const {
  if (candidates.empty()) return std::nullopt;
  if (state.size() != state_dims_) {
    throw std::invalid_argument("GreedyGqPredictor: dimension mismatch");
  }
  const double inverse_width_squared = 1.0 / (options_.width * options_.width);
  // θ_j times the state factor of φ_j; the config factor is multiplied in per candidate.
  std::vector<double> weighted(centres_.size());
  for (size_t j = 0; j < centres_.size(); ++j) {
    double squared = 0.0;
    for (size_t i = 0; i < state_dims_; ++i) {
      squared += (state[i] - centres_[j][i]) * (state[i] - centres_[j][i]);
    }
    weighted[j] = theta_[j] * std::exp(-squared * inverse_width_squared);
  }
  size_t best = 0;
  double best_q = -std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < candidates.size(); ++k) {
    const auto& a = candidates[k];
    if (a.size() != config_dims_) throw std::invalid_argument("GreedyGqPredictor: bad candidate");
    double q = theta_.back();
    for (size_t j = 0; j < centres_.size(); ++j) {
      const double* c = centres_[j].data() + state_dims_;
      double squared = 0.0;
      for (size_t i = 0; i < config_dims_; ++i) squared += (a[i] - c[i]) * (a[i] - c[i]);
      q += weighted[j] * std::exp(-squared * inverse_width_squared);
    }
    if (q > best_q) {
      best_q = q;
      best = k;
    }
  }
  return best;
}

double GreedyGqPredictor::reward(RewardKind kind, double cost, double worst_finite_cost) {
  const bool failed = !std::isfinite(cost);
  if (kind == RewardKind::kInverse) return failed ? 0.0 : 1.0 / cost;
  if (failed) cost = worst_finite_cost > 0.0 ? 10.0 * worst_finite_cost : 1e30;
  return -std::log(cost);
}

std::string GreedyGqPredictor::serialise() const {
  TokenWriter out;
  out.put_word("gq1")
      .put(static_cast<int64_t>(state_dims_))
      .put(static_cast<int64_t>(config_dims_));
  out.put(options_.width).put(static_cast<int64_t>(updates_)).put(theta_);
  out.put(static_cast<int64_t>(centres_.size()));
  for (const auto& c : centres_) out.put(c);
  return out.str();
}

void GreedyGqPredictor::restore(std::string_view text) {
  TokenReader in(text);
  if (in.get_word() != "gq1") throw std::runtime_error("not a Greedy-GQ model state");
  if (in.get_int() != static_cast<int64_t>(state_dims_) ||
      in.get_int() != static_cast<int64_t>(config_dims_)) {
    throw std::runtime_error("Greedy-GQ model state has other dimensions");
  }
  const double width = in.get_double();
  const auto updates = static_cast<uint64_t>(in.get_int());
  std::vector<double> theta = in.get_doubles();
  const int64_t count = in.get_int();
  if (count < 0 || theta.size() != static_cast<size_t>(count) + 1) {
    throw std::runtime_error("Greedy-GQ model state is inconsistent");
  }
  std::vector<std::vector<double>> centres;
  for (int64_t j = 0; j < count; ++j) {
    centres.push_back(in.get_doubles());
    if (centres.back().size() != state_dims_ + config_dims_) {
      throw std::runtime_error("Greedy-GQ model state has a bad centre");
    }
  }
  options_.width = width;
  updates_ = updates;
  theta_ = std::move(theta);
  centres_ = std::move(centres);
}

}  // namespace tuneray::tuner
