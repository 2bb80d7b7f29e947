// Every option of HybridTuner with its default.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tuner/greedy_gq.h"
#include "tuner/nelder_mead.h"

namespace tuneray::tuner {

enum class PredictorKind {
  kNearestNeighbour,  // best configuration of the nearest known state
  kRbf,               // Greedy-GQ: argmax of Q over the configurations past searches found
  // The state's own best if it has been measured; otherwise Greedy-GQ's argmax over the
  // candidates plus the nearest neighbour's configuration, if the model also picks the
  // neighbour's configuration at the neighbour's own state (else the neighbour's configuration).
  kBoth,
};

struct TunerOptions {
  // Probability of searching at a state change (otherwise one prediction is exploited until
  // the next state change). A state farther than nn_threshold from every known state, or any
  // state while nothing is known, is always searched.
  double epsilon = 0.1;
  PredictorKind predictor = PredictorKind::kBoth;
  // Seeds the policy's generator, from which every search and the RBF centres draw theirs.
  uint64_t seed = 1;
  // The search; its max_iterations (80) is the search budget per state.
  NelderMeadOptions search;
  // Configurations known to be good in general (e.g. an expert's settings): every new search
  // puts them in its first simplex beside its start point, so they are measured in each state
  // and the search starts from the best of them. Empty: start point and Latin Hypercube only.
  std::vector<Config> search_seeds;
  GreedyGqOptions gq;
  // -log cost trained better than 1/cost in our synthetic bandit test (see docs/tuner.md).
  RewardKind reward = RewardKind::kNegLog;
  // Two states whose normalised indicator vectors are closer than this are the same state.
  double state_tolerance = 1e-6;
  // Normalised distance beyond which the nearest known state is too far to predict from; the
  // state is then searched, warm-started from that state's best. Default: never too far.
  double nn_threshold = std::numeric_limits<double>::infinity();

  // Empty: nothing is persisted. Otherwise an SQLite file (see tuning_db.h).
  std::string db_path;
  // Namespace inside the file, so several objectives/applications can share it.
  std::string tuning_key = "default";
  // Empty: hardware_signature() (CPU model and core count). Samples of another signature are
  // not used.
  std::string hardware;
  // θ is written to the database every this many reports and when the tuner is destroyed;
  // samples recorded after the last snapshot are replayed into θ on opening.
  int model_snapshot_interval = 1000;
};

}  // namespace tuneray::tuner
