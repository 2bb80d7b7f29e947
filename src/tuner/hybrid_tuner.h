// HybridTuner: the online autotuner (DESIGN §5). In-process, ask/tell:
//
//   HybridTuner tuner(space, schema, options);
//   for (each input) {
//     Config c = tuner.suggest(state);   // state = indicator values of the current input
//     ... run with c, measure ...
//     tuner.report(c, seconds);          // or report_failure(c)
//   }
//
// Policy. suggest() compares the state with the previous one; when it differs by more than
// options.state_tolerance (normalised), epsilon-greedy chooses: explore (run, or resume, a
// Nelder-Mead search for this state, warm-started from the best known configuration for it or
// for its nearest neighbour) or exploit (one predicted configuration, returned until the next
// state change). A finished search hands over to its incumbent for the rest of the state.
// Every report, in either mode, is recorded (and written to the database) and trains both
// predictors. Searches of states left half-way are kept and resumed when the state returns.
//
// Cost: suggest/report are O(parameters) hash lookups plus 1 + options.gq.replays_per_sample
// RBF updates (features × dimensions each) and one SQLite transaction; a state change adds a scan
// of the known states and the candidate list. See bench/tuner for measured latencies.
//
// Not thread-safe: call from one thread (or guard it).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "tuner/config.h"
#include "tuner/greedy_gq.h"
#include "tuner/indicators.h"
#include "tuner/nearest_neighbour.h"
#include "tuner/nelder_mead.h"
#include "tuner/space.h"
#include "tuner/tuner_options.h"
#include "tuner/tuning_db.h"

namespace tuneray::tuner {

enum class TunerMode { kSearch, kExploit };

// Progress of one state, for evaluation and logging.
struct StateSummary {
  int64_t state_id = -1;
  State indicators;
  bool searched = false;   // a search has been run for it (finished or not)
  bool predicted = false;  // a prediction has been exploited for it
  bool searching = false;  // its search is unfinished
  bool converged = false;  // its last search met the convergence criterion
  int search_iterations = 0;
  std::optional<Config> incumbent;  // search incumbent, else the best measured configuration
  double incumbent_cost = 0.0;      // median of its costs (+infinity if unknown/failed)
  size_t samples = 0;
};

enum class TunerEventKind {
  kNewState,  // a state never seen before
  kSearchStarted,
  kSearchResumed,   // an unfinished search of a returning state continues
  kSearchFinished,  // config = incumbent; detail says whether it converged
  kPredicted,       // exploit: config = the prediction kept until the next state change
};

struct TunerEvent {
  TunerEventKind kind;
  int64_t state_id;
  std::optional<Config> config;
  std::string detail;
};

class HybridTuner {
 public:
  // Throws std::invalid_argument for bad options or a default configuration that violates a
  // constraint, TuningDbError for database problems. With a database, everything recorded for
  // (tuning_key, hardware) is loaded and the tuner continues where it stopped.
  HybridTuner(Space space, IndicatorSchema schema, TunerOptions options = {});
  ~HybridTuner();  // writes the model snapshot
  HybridTuner(const HybridTuner&) = delete;
  HybridTuner& operator=(const HybridTuner&) = delete;

  // The configuration to run for `state` now.
  Config suggest(const State& state);
  // Records a measurement of `config` in the state of the last suggest(). `cost` > 0, lower is
  // better (+infinity = failure). `extras` (e.g. build_ms, render_ms) are only stored.
  // Returns once the sample is committed to the database.
  void report(const Config& config, double cost, const Extras& extras = {});
  // The configuration failed (e.g. the BVH build failed): never chosen again as best, counts
  // as infinitely bad in the search, reward as in greedy_gq.h.
  void report_failure(const Config& config, const Extras& extras = {});

  // Best known configuration for `state`: its best measured one (lowest median) if the state is
  // known, else the prediction, else the default. Does not change the policy's state.
  Config best(const State& state) const;
  // The `count` best measured configurations for `state`, best first, ranked as best() ranks
  // them (failures never): the finalists a caller re-measures side by side, since the best of
  // many noisy samples is biased towards a lucky one. Empty for an unknown state.
  std::vector<Config> finalists(const State& state, size_t count) const;

  // Changes epsilon from the next state change on, e.g. to exploit only after training.
  void set_epsilon(double epsilon);

  TunerMode mode() const { return mode_; }
  std::optional<StateSummary> summary(const State& state) const;
  std::vector<StateSummary> summaries() const;
  size_t state_count() const { return states_.size(); }
  // Configurations past searches converged to (the exploit candidates).
  const std::vector<Config>& candidates() const { return candidates_; }
  void set_event_listener(std::function<void(const TunerEvent&)> listener) {
    listener_ = std::move(listener);
  }

  const Space& space() const { return space_; }
  const IndicatorSchema& schema() const { return schema_; }
  const TunerOptions& options() const { return options_; }
  TuningDb* database() { return db_.get(); }
  int64_t signature_id() const { return signature_; }
  const GreedyGqPredictor& gq() const { return gq_; }

 private:
  // Only the most recent kCostWindow costs of a configuration are kept in memory (all are in
  // the database): a configuration exploited for hours is measured every frame, and its median
  // must stay cheap to update and follow slow drifts of the machine.
  static constexpr size_t kCostWindow = 31;
  struct Measurements {
    std::vector<double> costs;  // the window, oldest first
    double median = 0.0;        // robust_cost(costs), cached
    size_t order = 0;           // first-measured order: breaks ties between equal medians
  };
  struct StateData {
    int64_t id = -1;
    State raw;
    std::vector<double> normalised;
    std::unordered_map<Config, Measurements> measurements;
    std::optional<Config> best;
    double best_cost = 0.0;
    std::optional<NelderMead> search;
    bool searched = false;
    bool predicted = false;
    size_t samples = 0;
  };
  struct Prediction {
    Config config;
    bool known;
  };

  StateData* find_state(const std::vector<double>& normalised) const;
  StateData& find_or_add_state(const State& raw, const std::vector<double>& normalised);
  void on_state_change(const State& raw, const std::vector<double>& normalised);
  std::optional<Prediction> predict(const StateData* state,
                                    const std::vector<double>& normalised) const;
  void start_search(StateData& state, const std::optional<Prediction>& prediction);
  void finish_search(StateData& state);
  // Adds a measurement to the in-memory tables and, if `train`, to θ (otherwise only to the
  // RBF predictor's replay memory).
  void record(StateData& state, const Config& config, double cost, bool train);
  // Re-chooses state.best after a measurement (see scores() for how noise is handled).
  void update_best(StateData& state);
  // A measured configuration's score (see scores() for why it is not the median); the lower
  // ranks first.
  struct Scored {
    double score;
    size_t order;  // first-measured order
    const Config* config;
    double median;
    bool operator<(const Scored& other) const;
  };
  // Every measured configuration of the state that did not fail, with its score, unordered.
  static std::vector<Scored> scores(const StateData& state);
  void add_candidate(const Config& config);
  NelderMead::Lookup lookup_for(const StateData& state) const;
  int64_t config_id(const Config& config);
  std::string policy_state() const;
  void load();
  void save_model();
  void emit(TunerEventKind kind, int64_t state_id, std::optional<Config> config = std::nullopt,
            std::string detail = {});

  Space space_;
  IndicatorSchema schema_;
  TunerOptions options_;
  NearestNeighbourPredictor nn_;
  GreedyGqPredictor gq_;
  Rng rng_;

  std::vector<std::unique_ptr<StateData>> states_;
  std::unordered_map<int64_t, StateData*> state_by_id_;
  StateData* current_ = nullptr;
  TunerMode mode_ = TunerMode::kExploit;
  std::optional<Config> exploit_;
  std::vector<Config> candidates_;
  std::vector<std::vector<double>> candidate_points_;
  std::unordered_set<Config> candidate_set_;
  double worst_finite_cost_ = 0.0;

  std::unique_ptr<TuningDb> db_;
  int64_t signature_ = 0;
  std::unordered_map<Config, int64_t> config_ids_;
  int64_t last_sample_id_ = 0;
  int64_t snapshot_sample_id_ = 0;
  int reports_since_snapshot_ = 0;
  int64_t next_local_state_id_ = 1;

  std::function<void(const TunerEvent&)> listener_;
};

}  // namespace tuneray::tuner
