// Greedy-GQ predictor with discount 0 (DESIGN §5): a linear value function
// Q(s, a) = θ · φ(s, a) over Gaussian radial basis features of x = (state, config), both
// normalised to [0,1].
//
// - Features: φ_j(x) = exp(-‖x - c_j‖² / width²), plus one constant (bias) feature so that the
//   mean reward need not be built out of bumps. Centres c_j: ceil(centres_per_dimension × dim)
//   [5] points by Latin Hypercube sampling of [0,1]^dim (seeded). width [1]. DESIGN §5 says
//   about 3.5 × dim; on our bandit test (tests/tuner/greedy_gq_test.cpp) 3.5 × dim picked a
//   configuration within 5 % of the optimum for 55 of 80 held-out states, 5 × dim for 78 of 80,
//   hence the default. Narrower widths (0.5, 0.7) were much worse, wider (1.5, 2) too.
// - Update: with discount 0 the GQ target is the immediate reward, so the TD error is
//   δ = R - θ·φ and θ += α δ φ / ‖φ‖² (step normalised by ‖φ‖², α = `step_size` [0.1]): a
//   normalised LMS step that moves Q(s,a) a fraction α of the way towards R whatever the scale
//   of the features. GQ's secondary weights w only multiply the discounted next-state term
//   γ φ(s',a')(w·φ); with γ = 0 that term vanishes, so w would be updated but never used. It is
//   not kept, because keeping it is not free (a second vector and update per sample).
// - Reward: RewardKind::kInverse (1/cost, as in the study) or RewardKind::kNegLog (-log cost).
//   -log cost turns a state-dependent scale factor (big inputs are slower for every
//   configuration) into an additive offset that the bias and state features absorb; with 1/cost
//   fast states dominate the squared error. Measured in tests/tuner (docs/tuner.md): kNegLog
//   picked within 5 % of the optimum for 78 of 80 held-out states, kInverse for 56 of 80, so
//   kNegLog is the default of TunerOptions.
// - A failed configuration gets reward 0 with kInverse (the limit of 1/cost) and, with kNegLog,
//   the reward of ten times the worst finite cost seen so far, so a failure is worse than every
//   success without an infinite value wrecking θ.
// - Experience replay: each train() is followed by `replays_per_sample` [32] updates on samples
//   drawn from the last `replay_memory` [4096] trained or remembered ones. An online tuner
//   trains once per report, state after state, and each normalised step pulls θ towards the
//   latest sample, so without replay the fit of earlier states fades: on the bandit of
//   tests/tuner, one pass in state order picks within 5 % for 12 of 80 held-out states, with 32
//   replays for 65 (200 shuffled passes: 78). The draws are a hash of the update count, so the
//   same sequence of samples gives the same θ bit for bit (a reopened database replays into θ
//   what came after its snapshot, and only remembers what came before).
// - Exploit: argmax of Q over a candidate list (the configurations past searches converged to).
//   φ factorises into a state part and a config part (the squared distance is a sum), so the
//   state part is computed once per query.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tuneray::tuner {

enum class RewardKind { kInverse, kNegLog };

struct GreedyGqOptions {
  double centres_per_dimension = 5.0;
  double width = 1.0;
  double step_size = 0.1;
  int replays_per_sample = 32;
  size_t replay_memory = 4096;
};

class GreedyGqPredictor {
 public:
  GreedyGqPredictor(size_t state_dims, size_t config_dims, const GreedyGqOptions& options,
                    uint64_t seed);

  // One update with a reward already computed by reward(), then the replays.
  void train(std::span<const double> state, std::span<const double> config, double reward);
  // Adds a sample to the replay memory without an update (samples already folded into a
  // restored θ).
  void remember(std::span<const double> state, std::span<const double> config, double reward);
  // φ(state, config), the bias last: training on a fixed set of samples over many passes
  // computes each sample's features once and trains on them (train_features).
  std::vector<double> feature_vector(std::span<const double> state,
                                     std::span<const double> config) const;
  // The update train() makes, on features from feature_vector().
  void train_features(std::span<const double> phi, double reward);
  double value(std::span<const double> state, std::span<const double> config) const;
  // Index of the candidate with the largest Q for `state`, nullopt for an empty list.
  std::optional<size_t> best_candidate(std::span<const double> state,
                                       const std::vector<std::vector<double>>& candidates) const;

  // Reward for a cost (+infinity = failure). `worst_finite_cost` is the largest finite cost
  // seen so far (used for failures with kNegLog).
  static double reward(RewardKind kind, double cost, double worst_finite_cost);

  size_t feature_count() const { return centres_.size() + 1; }
  const std::vector<double>& theta() const { return theta_; }
  uint64_t updates() const { return updates_; }
  size_t remembered() const { return memory_.size(); }

  // θ, centres and options, exactly.
  std::string serialise() const;
  // Throws std::runtime_error if the text does not match the dimensions.
  void restore(std::string_view text);

 private:
  void features(std::span<const double> state, std::span<const double> config,
                std::vector<double>& phi) const;
  struct Remembered {
    std::vector<double> point;  // state then config
    double reward;
  };

  size_t state_dims_;
  size_t config_dims_;
  GreedyGqOptions options_;
  std::vector<std::vector<double>> centres_;  // each of size state_dims + config_dims
  std::vector<double> theta_;                 // last entry: bias
  uint64_t updates_ = 0;
  std::vector<Remembered> memory_;  // a ring of at most options_.replay_memory samples
  size_t memory_next_ = 0;          // the slot the next sample overwrites once the ring is full
  mutable std::vector<double> scratch_;
};

}  // namespace tuneray::tuner
