#include "tuner/hybrid_tuner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "tuner/hardware_signature.h"
#include "tuner/token_io.h"

namespace tuneray::tuner {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

double squared_distance(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return sum;
}

void validate(const Space& space, const TunerOptions& options) {
  if (!(options.epsilon >= 0.0 && options.epsilon <= 1.0)) {
    throw std::invalid_argument("TunerOptions: epsilon must be in [0,1]");
  }
  if (!(options.state_tolerance >= 0.0)) {
    throw std::invalid_argument("TunerOptions: state_tolerance must be >= 0");
  }
  if (options.model_snapshot_interval < 1) {
    throw std::invalid_argument("TunerOptions: model_snapshot_interval must be >= 1");
  }
  if (!space.satisfies_constraints(space.default_config())) {
    throw std::invalid_argument("Space: the default configuration violates a constraint");
  }
  for (const Config& seed : options.search_seeds) {
    if (seed.size() != space.size() || !space.satisfies_constraints(seed)) {
      throw std::invalid_argument("TunerOptions: search seed '" + seed.to_string() +
                                  "' is not a feasible configuration of the space");
    }
  }
}

}  // namespace

HybridTuner::HybridTuner(Space space, IndicatorSchema schema, TunerOptions options)
    : space_(std::move(space)),
      schema_(std::move(schema)),
      options_(std::move(options)),
      nn_(options_.nn_threshold),
      gq_(schema_.size(), space_.size(), options_.gq, options_.seed),
      rng_(options_.seed) {
  validate(space_, options_);
  if (!options_.db_path.empty()) {
    if (options_.hardware.empty()) options_.hardware = hardware_signature();
    db_ = std::make_unique<TuningDb>(options_.db_path);
    signature_ = db_->open_signature(options_.tuning_key, options_.hardware, space_.describe(),
                                     schema_.describe());
    load();
  }
}

HybridTuner::~HybridTuner() {
  try {
    if (db_ && last_sample_id_ != snapshot_sample_id_) save_model();
  } catch (...) {
    // A destructor must not throw; the samples are safe and θ is rebuilt from them on opening.
  }
}

void HybridTuner::set_epsilon(double epsilon) {
  if (!(epsilon >= 0.0 && epsilon <= 1.0)) {
    throw std::invalid_argument("HybridTuner: epsilon must be in [0,1]");
  }
  options_.epsilon = epsilon;
}

void HybridTuner::emit(TunerEventKind kind, int64_t state_id, std::optional<Config> config,
                       std::string detail) {
  if (listener_) listener_(TunerEvent{kind, state_id, std::move(config), std::move(detail)});
}

HybridTuner::StateData* HybridTuner::find_state(const std::vector<double>& normalised) const {
  const double tolerance_squared = options_.state_tolerance * options_.state_tolerance;
  StateData* nearest = nullptr;
  double nearest_squared = kInfinity;
  for (const auto& state : states_) {
    const double squared = squared_distance(state->normalised, normalised);
    if (squared <= tolerance_squared && squared < nearest_squared) {
      nearest = state.get();
      nearest_squared = squared;
    }
  }
  return nearest;
}

HybridTuner::StateData& HybridTuner::find_or_add_state(const State& raw,
                                                       const std::vector<double>& normalised) {
  if (StateData* existing = find_state(normalised)) return *existing;
  auto state = std::make_unique<StateData>();
  state->id = db_ ? db_->add_state(signature_, raw) : next_local_state_id_++;
  state->raw = raw;
  state->normalised = normalised;
  StateData& added = *state;
  state_by_id_[added.id] = &added;
  states_.push_back(std::move(state));
  emit(TunerEventKind::kNewState, added.id);
  return added;
}

NelderMead::Lookup HybridTuner::lookup_for(const StateData& state) const {
  return [&state](const Config& config) -> const std::vector<double>* {
    const auto it = state.measurements.find(config);
    return it == state.measurements.end() ? nullptr : &it->second.costs;
  };
}

Config HybridTuner::suggest(const State& state) {
  std::vector<double> normalised = schema_.normalise(state);
  if (current_ == nullptr || squared_distance(current_->normalised, normalised) >
                                 options_.state_tolerance * options_.state_tolerance) {
    on_state_change(state, normalised);
  }
  if (mode_ == TunerMode::kSearch) {
    if (std::optional<Config> next = current_->search->next(lookup_for(*current_))) return *next;
    finish_search(*current_);
  }
  return *exploit_;
}

std::optional<HybridTuner::Prediction> HybridTuner::predict(
    const StateData* state, const std::vector<double>& normalised) const {
  const std::optional<NeighbourPrediction> neighbour = nn_.predict(normalised);
  const bool known = neighbour && neighbour->known;
  switch (options_.predictor) {
    case PredictorKind::kNearestNeighbour:
      if (!neighbour) return std::nullopt;
      return Prediction{neighbour->config, known};
    case PredictorKind::kRbf: {
      const std::optional<size_t> index = gq_.best_candidate(normalised, candidate_points_);
      if (!index) return std::nullopt;
      return Prediction{candidates_[*index], known};
    }
    case PredictorKind::kBoth: {
      if (state != nullptr && state->best && std::isfinite(state->best_cost)) {
        return Prediction{*state->best, true};
      }
      if (!neighbour) return std::nullopt;
      // The RBF overrides the nearest neighbour only if, at the neighbour's own state, it picks
      // the configuration measured best there: a model that cannot reproduce its nearest data
      // point (it cannot fit the problem) would spread one guess over every state.
      std::vector<std::vector<double>> points = candidate_points_;
      const auto it = std::find(candidates_.begin(), candidates_.end(), neighbour->config);
      const auto neighbour_index = static_cast<size_t>(it - candidates_.begin());
      if (it == candidates_.end()) points.push_back(space_.encode(neighbour->config));
      const size_t index = *gq_.best_candidate(normalised, points);
      if (index == neighbour_index) return Prediction{neighbour->config, known};
      const auto state_it = state_by_id_.find(neighbour->state_id);
      const bool consistent =
          state_it != state_by_id_.end() &&
          gq_.best_candidate(state_it->second->normalised, points) == neighbour_index;
      return Prediction{consistent ? candidates_[index] : neighbour->config, known};
    }
  }
  return std::nullopt;
}

void HybridTuner::on_state_change(const State& raw, const std::vector<double>& normalised) {
  StateData& state = find_or_add_state(raw, normalised);
  current_ = &state;
  const std::optional<Prediction> prediction = predict(&state, normalised);
  // Always draw, so that the sequence of draws does not depend on what is known.
  const double draw = rng_.uniform();
  const bool explore = !prediction || !prediction->known || draw < options_.epsilon;
  if (explore) {
    start_search(state, prediction);
  } else {
    mode_ = TunerMode::kExploit;
    exploit_ = prediction->config;
    state.predicted = true;
    emit(TunerEventKind::kPredicted, state.id, exploit_);
  }
}

void HybridTuner::start_search(StateData& state, const std::optional<Prediction>& prediction) {
  mode_ = TunerMode::kSearch;
  state.searched = true;
  if (state.search && !state.search->finished()) {
    emit(TunerEventKind::kSearchResumed, state.id);
    return;
  }
  const Config start = state.best && std::isfinite(state.best_cost) ? *state.best
                       : prediction                                 ? prediction->config
                                                                    : space_.default_config();
  std::vector<std::vector<double>> seeds;
  for (const Config& c : options_.search_seeds) seeds.push_back(space_.encode(c));
  state.search.emplace(space_, options_.search, space_.encode(start), rng_.next_u64(),
                       std::move(seeds));
  emit(TunerEventKind::kSearchStarted, state.id, start);
}

void HybridTuner::finish_search(StateData& state) {
  const Config incumbent = state.search->incumbent();
  mode_ = TunerMode::kExploit;
  exploit_ = incumbent;
  const auto it = state.measurements.find(incumbent);
  const bool measured_ok = it != state.measurements.end() && std::isfinite(it->second.median);
  std::optional<TuningDb::Transaction> transaction;
  if (db_) transaction.emplace(*db_);
  if (measured_ok) add_candidate(incumbent);
  if (db_) {
    db_->put_search(signature_, state.id, state.search->serialise());
    db_->put_tuner_state(signature_, policy_state());
    transaction->commit();
  }
  emit(TunerEventKind::kSearchFinished, state.id, incumbent,
       state.search->converged() ? "converged" : "budget or restarts exhausted");
}

void HybridTuner::add_candidate(const Config& config) {
  if (!candidate_set_.insert(config).second) return;
  candidates_.push_back(config);
  candidate_points_.push_back(space_.encode(config));
  if (db_) db_->add_candidate(signature_, config_id(config));
}

int64_t HybridTuner::config_id(const Config& config) {
  const auto it = config_ids_.find(config);
  if (it != config_ids_.end()) return it->second;
  const int64_t id = db_->config_id(signature_, config.to_string());
  config_ids_.emplace(config, id);
  return id;
}

// The lowest median alone would favour a configuration measured once on a lucky frame over one
// measured many times (the winner's curse: in a noisy search, a configuration measured once at
// 7.4 ms beat one measured 7 times with a median of 8.3 ms, and it is the slower one). So each
// median is shrunk towards the state's typical cost by one pseudo-measurement,
// (n median + prior) / (n + 1) with prior = the median of the configurations' medians: a
// configuration must beat the others by more than the noise of one frame, or be measured again,
// to become the best. Configurations measured equally often keep the order of their medians.
std::vector<HybridTuner::Scored> HybridTuner::scores(const StateData& state) {
  std::vector<double> medians;
  for (const auto& entry : state.measurements)
    if (std::isfinite(entry.second.median)) medians.push_back(entry.second.median);
  const double prior = robust_cost(medians);
  std::vector<Scored> scored;
  for (const auto& [candidate, m] : state.measurements) {
    if (!std::isfinite(m.median)) continue;  // failed: never the best
    const double n = static_cast<double>(m.costs.size());
    scored.push_back({(n * m.median + prior) / (n + 1.0), m.order, &candidate, m.median});
  }
  return scored;
}

bool HybridTuner::Scored::operator<(const Scored& other) const {
  // Equal scores: the configuration measured first.
  return std::tie(score, order) < std::tie(other.score, other.order);
}

void HybridTuner::update_best(StateData& state) {
  const std::vector<Scored> scored = scores(state);
  const auto best = std::min_element(scored.begin(), scored.end());
  if (best == scored.end()) {
    state.best.reset();
    state.best_cost = kInfinity;
    return;
  }
  state.best = *best->config;
  state.best_cost = best->median;
  nn_.set_best(state.id, state.normalised, *state.best);
}

void HybridTuner::record(StateData& state, const Config& config, double cost, bool train) {
  auto [it, inserted] = state.measurements.try_emplace(config);
  Measurements& m = it->second;
  if (inserted) m.order = state.measurements.size() - 1;
  if (m.costs.size() == kCostWindow) m.costs.erase(m.costs.begin());
  m.costs.push_back(cost);
  m.median = robust_cost(m.costs);
  ++state.samples;
  update_best(state);
  if (std::isfinite(cost)) worst_finite_cost_ = std::max(worst_finite_cost_, cost);
  const double reward = GreedyGqPredictor::reward(options_.reward, cost, worst_finite_cost_);
  if (train) {
    gq_.train(state.normalised, space_.encode(config), reward);
  } else {
    gq_.remember(state.normalised, space_.encode(config), reward);
  }
}

void HybridTuner::report(const Config& reported, double cost, const Extras& extras) {
  if (current_ == nullptr) throw std::logic_error("HybridTuner::report before suggest");
  if (reported.size() != space_.size()) {
    throw std::invalid_argument("HybridTuner::report: configuration of another space");
  }
  if (std::isnan(cost) || cost < 0.0) {
    throw std::invalid_argument("HybridTuner::report: cost must be >= 0 (+infinity = failure)");
  }
  const Config config = space_.canonical(reported);
  record(*current_, config, cost, true);
  if (!db_) return;
  TuningDb::Transaction transaction(*db_);
  last_sample_id_ = db_->add_sample(signature_, current_->id, config_id(config), cost, extras);
  if (mode_ == TunerMode::kSearch) {
    db_->put_search(signature_, current_->id, current_->search->serialise());
  }
  db_->put_tuner_state(signature_, policy_state());
  transaction.commit();
  if (++reports_since_snapshot_ >= options_.model_snapshot_interval) save_model();
}

void HybridTuner::report_failure(const Config& config, const Extras& extras) {
  report(config, kInfinity, extras);
}

Config HybridTuner::best(const State& state) const {
  const std::vector<double> normalised = schema_.normalise(state);
  const StateData* known = find_state(normalised);
  if (known && known->best && std::isfinite(known->best_cost)) return *known->best;
  if (std::optional<Prediction> prediction = predict(known, normalised)) {
    return prediction->config;
  }
  return space_.default_config();
}

std::vector<Config> HybridTuner::finalists(const State& state, size_t count) const {
  std::vector<Config> out;
  const StateData* known = find_state(schema_.normalise(state));
  if (known == nullptr) return out;
  std::vector<Scored> scored = scores(*known);
  const auto end = scored.begin() + static_cast<std::ptrdiff_t>(std::min(count, scored.size()));
  std::partial_sort(scored.begin(), end, scored.end());
  for (auto it = scored.begin(); it != end; ++it) out.push_back(*it->config);
  return out;
}

std::optional<StateSummary> HybridTuner::summary(const State& state) const {
  const StateData* data = find_state(schema_.normalise(state));
  if (data == nullptr) return std::nullopt;
  StateSummary s;
  s.state_id = data->id;
  s.indicators = data->raw;
  s.searched = data->searched;
  s.predicted = data->predicted;
  s.samples = data->samples;
  if (data->search) {
    s.searching = !data->search->finished();
    s.converged = data->search->converged();
    s.search_iterations = data->search->iterations();
    s.incumbent = data->search->incumbent();
  } else if (data->best) {
    s.incumbent = data->best;
  }
  s.incumbent_cost = kInfinity;
  if (s.incumbent) {
    const auto it = data->measurements.find(*s.incumbent);
    if (it != data->measurements.end()) s.incumbent_cost = it->second.median;
  }
  return s;
}

std::vector<StateSummary> HybridTuner::summaries() const {
  std::vector<StateSummary> result;
  for (const auto& state : states_) result.push_back(*summary(state->raw));
  return result;
}

std::string HybridTuner::policy_state() const {
  TokenWriter out;
  out.put_word("policy1").put(current_ ? current_->id : int64_t{-1});
  out.put(static_cast<int64_t>(mode_ == TunerMode::kSearch ? 1 : 0));
  out.put_word(exploit_ ? exploit_->to_string() : std::string()).put(rng_);
  return out.str();
}

void HybridTuner::save_model() {
  db_->put_model(signature_, last_sample_id_, gq_.serialise());
  snapshot_sample_id_ = last_sample_id_;
  reports_since_snapshot_ = 0;
}

void HybridTuner::load() {
  for (const StoredState& stored : db_->states(signature_)) {
    if (stored.indicators.size() != schema_.size()) {
      throw TuningDbError("tuning database " + db_->path() + ": state with wrong dimension");
    }
    auto state = std::make_unique<StateData>();
    state->id = stored.id;
    state->raw = stored.indicators;
    state->normalised = schema_.normalise(stored.indicators);
    state_by_id_[stored.id] = state.get();
    states_.push_back(std::move(state));
  }
  int64_t model_watermark = 0;
  if (auto model = db_->model(signature_)) {
    gq_.restore(model->second);
    model_watermark = model->first;
  }
  std::unordered_map<int64_t, Config> configs_by_id;
  // Replays every sample in recording order, exactly as report() processed it, so that bests,
  // the failure reward and θ (for samples after the snapshot) come out bit-identical.
  for (const StoredSample& sample : db_->samples(signature_)) {
    auto config_it = configs_by_id.find(sample.config_id);
    if (config_it == configs_by_id.end()) {
      config_it = configs_by_id.emplace(sample.config_id, space_.parse(sample.config)).first;
      config_ids_.emplace(config_it->second, sample.config_id);
    }
    const auto state_it = state_by_id_.find(sample.state_id);
    if (state_it == state_by_id_.end()) {
      throw TuningDbError("tuning database " + db_->path() + ": sample of an unknown state");
    }
    record(*state_it->second, config_it->second, sample.cost, sample.id > model_watermark);
    last_sample_id_ = sample.id;
  }
  snapshot_sample_id_ = model_watermark;
  for (const auto& [state_id, text] : db_->searches(signature_)) {
    const auto it = state_by_id_.find(state_id);
    if (it == state_by_id_.end()) continue;
    it->second->search.emplace(NelderMead::deserialise(space_, options_.search, text));
    it->second->searched = true;
  }
  for (int64_t id : db_->candidates(signature_)) {
    const Config config = space_.parse(db_->config_text(id));
    if (candidate_set_.insert(config).second) {
      candidates_.push_back(config);
      candidate_points_.push_back(space_.encode(config));
    }
  }
  if (const std::optional<std::string> text = db_->tuner_state(signature_)) {
    TokenReader in(*text);
    if (in.get_word() != "policy1") {
      throw TuningDbError("tuning database " + db_->path() + ": unknown policy state");
    }
    const int64_t current_id = in.get_int();
    const bool searching = in.get_int() != 0;
    const std::string exploit = in.get_word();
    in.get(rng_);
    const auto it = state_by_id_.find(current_id);
    current_ = it == state_by_id_.end() ? nullptr : it->second;
    mode_ = searching && current_ && current_->search ? TunerMode::kSearch : TunerMode::kExploit;
    if (!exploit.empty()) exploit_ = space_.parse(exploit);
    if (mode_ == TunerMode::kExploit && !exploit_) current_ = nullptr;  // re-decide on suggest
  }
}

}  // namespace tuneray::tuner
