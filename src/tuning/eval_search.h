// One camera's search in the study: its keys in the tuning database, its tuner, and its frames,
// either measured here or replayed. A replayed frame is one another rank measured: fed to a
// tuner with the same options and history, the tuner must suggest the very configuration the
// other rank measured (the search is deterministic given its costs), which is what lets rank 0
// store an MPI run's frames exactly as a single-rank run stores its own.
#pragma once

#include <string>

#include "tuner/hybrid_tuner.h"
#include "tuner/tuning_db.h"
#include "tuning/eval_costs.h"
#include "tuning/eval_profile.h"

namespace tuneray {

// One search frame as the tuner was told it.
struct EvalFrame {
  std::string config;  // tuner::Config::to_string() of the suggestion
  bool ok = true;      // false: the build was refused, reported as a failure
  double cost_s = 0;   // the reported cost (seconds) when ok
  double build_ms = 0, render_ms = 0;
  // The default configuration's cost (ms) measured right after this frame as the search window's
  // yardstick, not reported to the tuner; 0 when none was measured after this frame.
  double yardstick_ms = 0;
};

// Whether search frame `k` (from 0) is followed by a yardstick frame: profile.yardsticks of them
// spread evenly over the search, the last after its last frame.
bool yardstick_after_frame(const EvalProfile& p, int k);

// The name a scene spec goes by in keys and the report (its file stem).
std::string eval_scene_name(const std::string& spec);

// Key of one scene and objective: the scheduler is part of it (costs on tiles and on waves do
// not compare), and so are synthetic costs (they must never mix with measured ones).
std::string eval_run_key(const EvalProfile& p, const std::string& scene, Objective objective);

// Tuning key of one camera's search. The space is part of it (the database refuses one key with
// two spaces), and so are the seeds (a seeded search is another search).
std::string eval_tuning_key(const EvalProfile& p, const std::string& run_key, int camera);

tuner::Space eval_space(const EvalProfile& p);

// Options of one camera's search, without database (db_path and hardware are the caller's).
tuner::TunerOptions eval_tuner_options(const EvalProfile& p, Objective objective,
                                       const std::string& run_key, int camera);

// Suggests, measures and reports search frame `k` (from 0), then measures the yardstick if
// yardstick_after_frame(p, k).
EvalFrame measure_search_frame(const EvalProfile& p, int k, tuner::HybridTuner& tuner,
                               const tuner::State& state, EvalCostSource& costs,
                               Objective objective, int camera);

// Suggests and reports `frame` without measuring; throws std::runtime_error if the tuner
// suggests another configuration than the one `frame` measured.
void replay_search_frame(tuner::HybridTuner& tuner, const tuner::State& state,
                         const EvalFrame& frame);

// A sample of the database as the frame that recorded it.
EvalFrame stored_frame(const tuner::StoredSample& sample);

}  // namespace tuneray
